#include "batch/thread_pool.hpp"

#include <atomic>
#include <exception>

namespace footpoint {

ThreadPool::ThreadPool(unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  workers_.reserve(threads);
  for (unsigned i = 0; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
  for (auto& w : workers_) w.join();
}

std::size_t ThreadPool::queued() const {
  std::lock_guard lock(mutex_);
  return tasks_.size();
}

void ThreadPool::worker_loop() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) return;  // stopping and drained
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    task();
  }
}

void ThreadPool::parallel_for(std::size_t n, std::size_t chunk,
                              const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  if (chunk == 0) chunk = 1;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  // Completion state shared by this call's chunks only.
  struct Join {
    std::mutex mutex;
    std::condition_variable done;
    std::size_t remaining;
    std::exception_ptr error;
  } join;
  join.remaining = chunks;
  {
    std::lock_guard lock(mutex_);
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t begin = c * chunk, end = std::min(n, begin + chunk);
      tasks_.emplace_back([&join, &body, begin, end] {
        std::exception_ptr error;
        try {
          body(begin, end);
        } catch (...) {
          error = std::current_exception();
        }
        std::lock_guard lock(join.mutex);
        if (error && !join.error) join.error = error;
        if (--join.remaining == 0) join.done.notify_all();
      });
    }
  }
  cv_.notify_all();
  std::unique_lock lock(join.mutex);
  join.done.wait(lock, [&] { return join.remaining == 0; });
  if (join.error) std::rethrow_exception(join.error);
}

}  // namespace footpoint
