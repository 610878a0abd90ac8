#include "batch/thread_pool.hpp"

namespace footpoint {

// One parallel_for call. Chunks are claimed under the pool's mutex; completion is counted under the
// job's own mutex, which the submitting thread waits on.
struct ThreadPool::Job {
  const std::function<void(std::size_t, std::size_t)>* body = nullptr;
  std::size_t n = 0, chunk = 1, chunks = 0;
  std::size_t next = 0;  // next chunk to start (pool mutex)
  std::mutex mutex;
  std::condition_variable done;
  std::size_t remaining = 0;  // chunks not finished (job mutex)
  std::exception_ptr error;
};

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
  return jobs_.size();
}

void ThreadPool::worker_loop() {
  for (;;) {
    std::shared_ptr<Job> job;
    std::size_t c = 0;
    {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping and drained
      job = jobs_.front();
      jobs_.pop_front();
      c = job->next++;
      if (job->next < job->chunks) jobs_.push_back(job);  // round-robin between jobs
    }
    const std::size_t begin = c * job->chunk, end = std::min(job->n, begin + job->chunk);
    std::exception_ptr error;
    try {
      (*job->body)(begin, end);
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard lock(job->mutex);
    if (error && !job->error) job->error = error;
    if (--job->remaining == 0) job->done.notify_all();
  }
}

void ThreadPool::parallel_for(std::size_t n, std::size_t chunk,
                              const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  auto job = std::make_shared<Job>();
  job->body = &body;
  job->n = n;
  job->chunk = chunk == 0 ? 1 : chunk;
  job->chunks = (n + job->chunk - 1) / job->chunk;
  job->remaining = job->chunks;
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(job);
  }
  if (job->chunks == 1)
    cv_.notify_one();
  else
    cv_.notify_all();
  std::unique_lock lock(job->mutex);
  job->done.wait(lock, [&] { return job->remaining == 0; });
  if (job->error) std::rethrow_exception(job->error);
}

}  // namespace footpoint
