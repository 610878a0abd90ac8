// SIGTERM and SIGINT start a graceful shutdown; SIGHUP asks to read the keys and the TLS files
// again. They are blocked in every thread (call block_shutdown_signals() before starting any) and
// taken synchronously by one waiting thread, so the shutdown and the reload run as ordinary code,
// not in a signal handler.
#pragma once
#include <functional>

namespace footpoint::server {

void block_shutdown_signals();
// Blocks until SIGTERM or SIGINT arrives; returns the signal number. Each SIGHUP meanwhile calls
// `on_hangup` (when given) on this thread.
int wait_for_shutdown_signal(const std::function<void()>& on_hangup = {});

}  // namespace footpoint::server
