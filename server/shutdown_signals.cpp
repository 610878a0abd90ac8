#include "shutdown_signals.hpp"

#include <pthread.h>
#include <csignal>

namespace footpoint::server {

namespace {

sigset_t shutdown_set() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  return set;
}

}  // namespace

void block_shutdown_signals() {
  const sigset_t set = shutdown_set();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  // A peer closing its connection mid-response must not kill the process.
  signal(SIGPIPE, SIG_IGN);
}

int wait_for_shutdown_signal(const std::function<void()>& on_hangup) {
  const sigset_t set = shutdown_set();
  for (;;) {
    int sig = 0;
    if (sigwait(&set, &sig) != 0) continue;
    if (sig != SIGHUP) return sig;
    if (on_hangup) on_hangup();
  }
}

}  // namespace footpoint::server
