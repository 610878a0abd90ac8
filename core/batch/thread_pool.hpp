// A fixed pool of worker threads that runs the numerical work of every request. Each call of
// parallel_for is a job split into chunks; workers take one chunk at a time from the job at the front
// of the queue and put the job back at the end, so concurrent jobs share the workers round-robin
// (a single point is not stuck behind a 100,000-point batch that arrived first). The submitting
// thread waits for its own job only.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace footpoint {

// The CPUs this process may use: the cgroup's CPU quota rounded up (cgroup v2 `cpu.max`
// "quota period"; v1 `cpu.cfs_quota_us` / `cpu.cfs_period_us`; "max" or -1 is no quota), at most
// `hardware`; without a quota, `hardware`. `cgroup_root` is where the cgroup file system is
// mounted (/sys/fs/cgroup; in a container its own cgroup). At least 1.
unsigned cpus_of_cgroup(const std::string& cgroup_root, unsigned hardware);
// What a thread count of 0 stands for: cpus_of_cgroup("/sys/fs/cgroup", hardware_concurrency()).
unsigned default_threads();

class ThreadPool {
 public:
  explicit ThreadPool(unsigned threads);  // 0 -> default_threads()
  ~ThreadPool();                          // finishes queued tasks, then joins
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()); }
  std::size_t queued() const;  // jobs with chunks not yet started

  // Runs body(begin, end) over [0, n) in chunks of at most `chunk` items on the pool and returns
  // when all chunks are done. Exceptions thrown by body are rethrown here (the first one).
  void parallel_for(std::size_t n, std::size_t chunk,
                    const std::function<void(std::size_t, std::size_t)>& body);

 private:
  struct Job;
  void worker_loop();
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::shared_ptr<Job>> jobs_;
  std::vector<std::thread> workers_;
  bool stopping_ = false;
};

}  // namespace footpoint
