// A fixed pool of worker threads that runs the numerical work of every request. Batches are split
// into chunks (tasks); the submitting thread waits for its own chunks only.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace footpoint {

class ThreadPool {
 public:
  explicit ThreadPool(unsigned threads);  // 0 -> std::thread::hardware_concurrency()
  ~ThreadPool();                          // finishes queued tasks, then joins
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()); }
  std::size_t queued() const;

  // Runs body(begin, end) over [0, n) in chunks of at most `chunk` items on the pool and returns
  // when all chunks are done. Exceptions thrown by body are rethrown here (the first one).
  void parallel_for(std::size_t n, std::size_t chunk,
                    const std::function<void(std::size_t, std::size_t)>& body);

 private:
  void worker_loop();
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> tasks_;
  std::vector<std::thread> workers_;
  bool stopping_ = false;
};

}  // namespace footpoint
