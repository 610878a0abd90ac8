#include "batch/thread_pool.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <utility>

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

// One parallel_for call. Grains are claimed under the pool's mutex (next); completion is counted
// under the job's own mutex, which the submitting thread waits on.
struct ThreadPool::Job {
  const std::function<void(std::size_t, std::size_t)>* body = nullptr;
  const JobOptions* options = nullptr;
  std::size_t n = 0, max_grain = 1;
  std::size_t next = 0;                // first item not claimed (pool mutex)
  std::atomic<std::size_t> grain{0};   // items of the next grain (see thread_pool.hpp)
  std::atomic<bool> cancelled{false};  // options->cancelled answered true
  std::mutex mutex;
  std::condition_variable done;
  std::size_t remaining = 0;  // items neither run nor dropped (job mutex)
  std::size_t dropped = 0;    // items dropped by cancellation (job mutex)
  std::exception_ptr error;
};

// A tenant's jobs with grains not yet claimed, in turn order.
struct ThreadPool::Tenant {
  std::string name;
  std::deque<std::shared_ptr<Job>> jobs;
};

ThreadPool::ThreadPool(unsigned threads, std::chrono::nanoseconds grain_time)
    : grain_time_(grain_time.count() > 0 ? grain_time : std::chrono::nanoseconds(1)) {
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
  std::size_t jobs = 0;
  for (const auto& tenant : ready_)
    for (const auto& job : tenant->jobs) jobs += job->next < job->n ? 1 : 0;
  return jobs;
}

bool ThreadPool::claim(std::shared_ptr<Job>& job, std::size_t& begin, std::size_t& end) {
  while (!ready_.empty()) {
    std::shared_ptr<Tenant> tenant = std::move(ready_.front());
    ready_.pop_front();
    while (!tenant->jobs.empty()) {
      std::shared_ptr<Job> candidate = std::move(tenant->jobs.front());
      tenant->jobs.pop_front();
      if (candidate->next >= candidate->n) continue;  // its grains were dropped
      begin = candidate->next;
      end = begin + std::min(candidate->grain.load(std::memory_order_relaxed), candidate->n - begin);
      candidate->next = end;
      if (end < candidate->n) tenant->jobs.push_back(candidate);       // the tenant's jobs take turns
      if (!tenant->jobs.empty()) ready_.push_back(std::move(tenant));  // so do the tenants
      job = std::move(candidate);
      return true;
    }
  }
  return false;
}

void ThreadPool::run_grain(Job& job, std::size_t begin, std::size_t end) {
  const std::size_t items = end - begin;
  std::size_t dropped = 0;
  std::exception_ptr error;
  if (begin > 0 && job.options->cancelled && !job.cancelled.load() && job.options->cancelled())
    job.cancelled.store(true);
  if (job.cancelled.load()) {
    std::lock_guard lock(mutex_);
    dropped = items + (job.n - job.next);
    job.next = job.n;
  } else {
    const auto start = std::chrono::steady_clock::now();
    try {
      (*job.body)(begin, end);
    } catch (...) {
      error = std::current_exception();
    }
    // The next grain lasts about grain_time_ at this grain's speed, at most four times this one.
    const double elapsed =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    const double target =
        elapsed > 0.0 ? static_cast<double>(grain_time_.count()) * static_cast<double>(items) / elapsed
                      : static_cast<double>(job.max_grain);
    const double grain = std::clamp(std::min(target, 4.0 * static_cast<double>(items)), 1.0,
                                    static_cast<double>(job.max_grain));
    job.grain.store(static_cast<std::size_t>(grain), std::memory_order_relaxed);
  }
  std::lock_guard lock(job.mutex);
  // The first error is moved into the job, and the caller takes it out (parallel_for): whichever
  // thread drops the job last, only the caller's thread then holds the exception and frees it.
  if (error && !job.error) job.error = std::move(error);
  job.dropped += dropped;
  job.remaining -= dropped > 0 ? dropped : items;
  if (job.remaining == 0) job.done.notify_all();
}

void ThreadPool::worker_loop() {
  for (;;) {
    std::shared_ptr<Job> job;
    std::size_t begin = 0, end = 0;
    {
      std::unique_lock lock(mutex_);
      while (!claim(job, begin, end)) {
        if (stopping_) return;  // stopping and drained
        cv_.wait(lock);
      }
    }
    run_grain(*job, begin, end);
  }
}

std::size_t ThreadPool::parallel_for(std::size_t n, std::size_t max_grain,
                                     const std::function<void(std::size_t, std::size_t)>& body,
                                     const JobOptions& options) {
  if (n == 0) return 0;
  auto job = std::make_shared<Job>();
  job->body = &body;
  job->options = &options;
  job->n = n;
  job->max_grain = max_grain == 0 ? 1 : max_grain;
  job->grain = std::min(kFirstGrain, job->max_grain);
  job->remaining = n;
  {
    std::lock_guard lock(mutex_);
    auto tenant = std::find_if(ready_.begin(), ready_.end(),
                               [&](const std::shared_ptr<Tenant>& t) { return t->name == options.tenant; });
    if (tenant == ready_.end()) {
      ready_.push_back(std::make_shared<Tenant>());
      ready_.back()->name = options.tenant;
      tenant = std::prev(ready_.end());
    }
    (*tenant)->jobs.push_back(job);
  }
  if (n == 1)
    cv_.notify_one();
  else
    cv_.notify_all();
  std::unique_lock lock(job->mutex);
  job->done.wait(lock, [&] { return job->remaining == 0; });
  if (job->error) std::rethrow_exception(std::exchange(job->error, nullptr));
  return n - job->dropped;
}

}  // namespace footpoint
