#include "batch/thread_pool.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace footpoint {

namespace {

// The CPUs a quota of `quota` microseconds per `period` gives: ceil(quota / period); 0 for none.
unsigned quota_cpus(double quota, double period) {
  if (!(quota > 0.0) || !(period > 0.0)) return 0;
  return static_cast<unsigned>(std::min(std::ceil(quota / period), 65536.0));
}

// cgroup v2: "max 100000" (no quota) or "200000 100000".
unsigned cgroup_v2_cpus(const std::string& root) {
  std::ifstream in(root + "/cpu.max");
  std::string quota;
  double period = 0.0;
  if (!(in >> quota >> period) || quota == "max") return 0;
  try {
    return quota_cpus(std::stod(quota), period);
  } catch (const std::exception&) {
    return 0;
  }
}

// cgroup v1: cpu.cfs_quota_us (-1: no quota) and cpu.cfs_period_us, under cpu/ or cpu,cpuacct/.
unsigned cgroup_v1_cpus(const std::string& root) {
  for (const char* controller : {"/cpu", "/cpu,cpuacct"}) {
    std::ifstream q(root + controller + "/cpu.cfs_quota_us"), p(root + controller + "/cpu.cfs_period_us");
    double quota = 0.0, period = 0.0;
    if (q >> quota && p >> period) return quota_cpus(quota, period);
  }
  return 0;
}

}  // namespace

unsigned cpus_of_cgroup(const std::string& cgroup_root, unsigned hardware) {
  hardware = std::max(1u, hardware);
  unsigned quota = cgroup_v2_cpus(cgroup_root);
  if (quota == 0) quota = cgroup_v1_cpus(cgroup_root);
  return quota == 0 ? hardware : std::clamp(quota, 1u, hardware);
}

unsigned default_threads() { return cpus_of_cgroup("/sys/fs/cgroup", std::thread::hardware_concurrency()); }

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
  if (threads == 0) threads = default_threads();
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
