// The registry tests need a real redis-server; without one the whole suite is skipped (exit 77,
// which ctest reports as "Skipped") with a message that says what to install.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <csignal>
#include <cstdio>

#include "registry_support.hpp"

int main(int argc, char** argv) {
  if (footpoint::registry_testing::redis_server_path().empty()) {
    std::puts(
        "SKIPPED: redis-server not found (apt-get install redis-server, or set FOOTPOINT_REDIS_SERVER)");
    return 77;
  }
  std::signal(SIGPIPE, SIG_IGN);
  doctest::Context context(argc, argv);
  return context.run();
}
