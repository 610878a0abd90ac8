// A fixed pool of worker threads that runs the numerical work of every request.
//
// Each call of parallel_for is a job over the items [0, n). Workers take one grain (a run of
// consecutive items) at a time, and grains are sized by time, not by count: a job's first grain is
// kFirstGrain items (project_batch reads the clock for its deadline before every fourth point of a
// grain: a batch of up to four points is one grain, one read), and after each grain the next is
// sized so that it lasts about `grain_time` at the speed just measured (growing at most fourfold
// per grain, never above the caller's maximum). A worker is therefore never busy with one job for
// much longer than `grain_time` before it looks at the queue again, whatever a point costs (a
// plane's foot point or a surface covering itself many times), while a grain still holds enough
// items that claiming it costs a negligible share.
//
// Fairness: jobs are queued per tenant (an opaque label; the server passes the API key's name,
// "" without keys). Workers serve the tenants with waiting grains round-robin, one grain each, and
// each tenant's jobs round-robin, one grain each (round-robin with grains of about equal time is
// a fair share of the workers' time: Nagle's fair queueing, RFC 970; Shreedhar and Varghese,
// "Efficient fair queuing using deficit round robin", 1995, with a time quantum). A single point
// submitted while large batches run waits for the grains in progress (about grain_time) and for
// one grain of each tenant ahead of it in the rotation, never for a batch's queued grains; one
// tenant's flood of batches takes one turn per round however many jobs it has queued.
//
// Cancellation: a job may carry a predicate asked before each of its grains after the first; when
// it answers true the job's grains not yet started are dropped and parallel_for returns the number
// of items that ran. The submitting thread waits for its own job only.
#pragma once
#include <atomic>
#include <chrono>
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

struct JobOptions {
  std::string tenant;  // the queue the job waits in (see above); "" is a tenant like any other
  // Asked by a worker before each grain of the job after the first (from any worker thread, so it
  // must be thread-safe); true drops the grains not yet started. Empty: never cancelled.
  std::function<bool()> cancelled;
};

class ThreadPool {
 public:
  // The time a grain aims at (see above).
  static constexpr std::chrono::microseconds kDefaultGrainTime{500};
  // The items of a job's first grain (at most the caller's maximum).
  static constexpr std::size_t kFirstGrain = 4;

  explicit ThreadPool(unsigned threads,  // 0 -> default_threads()
                      std::chrono::nanoseconds grain_time = kDefaultGrainTime);
  ~ThreadPool();  // finishes queued jobs, then joins
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()); }
  std::size_t queued() const;  // jobs with grains not yet started

  // Runs body(begin, end) over [0, n) in grains of at most `max_grain` items on the pool and
  // returns when all grains are done (or dropped by options.cancelled): the number of items run,
  // n unless cancelled. Exceptions thrown by body are rethrown here (the first one).
  std::size_t parallel_for(std::size_t n, std::size_t max_grain,
                           const std::function<void(std::size_t, std::size_t)>& body,
                           const JobOptions& options = {});

 private:
  struct Job;
  struct Tenant;
  // Takes the next grain in the rotation (pool mutex held); false when there is none.
  bool claim(std::shared_ptr<Job>& job, std::size_t& begin, std::size_t& end);
  void run_grain(Job& job, std::size_t begin, std::size_t end);
  void worker_loop();

  const std::chrono::nanoseconds grain_time_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::shared_ptr<Tenant>> ready_;  // tenants with grains not started, in turn order
  std::vector<std::thread> workers_;
  bool stopping_ = false;
};

}  // namespace footpoint
