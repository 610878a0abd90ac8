// SIGTERM and SIGINT start a graceful shutdown. They are blocked in every thread (call
// block_shutdown_signals() before starting any) and taken synchronously by one waiting thread,
// so the shutdown runs as ordinary code, not in a signal handler.
#pragma once

namespace footpoint::server {

void block_shutdown_signals();
// Blocks until SIGTERM or SIGINT arrives; returns the signal number.
int wait_for_shutdown_signal();

}  // namespace footpoint::server
