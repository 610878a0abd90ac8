// The core's thread pool: every index runs exactly once, grains honour their bounds, exceptions
// reach the caller, concurrent callers share the pool safely, grains are sized by time, tenants
// take turns, and a cancelled job drops its grains not started. The scheduling tests count grains
// and items, never wall time.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "batch/thread_pool.hpp"

using footpoint::JobOptions;
using footpoint::ThreadPool;

TEST_CASE("parallel_for visits every index once, in chunks of at most the given size") {
  for (unsigned threads : {1u, 2u, 4u}) {
    ThreadPool pool(threads);
    CHECK(pool.size() == threads);
    for (std::size_t n : {0u, 1u, 7u, 1000u, 12345u}) {
      std::vector<std::atomic<int>> seen(n);
      std::atomic<std::size_t> max_chunk{0};
      pool.parallel_for(n, 64, [&](std::size_t b, std::size_t e) {
        std::size_t len = e - b, prev = max_chunk.load();
        while (len > prev && !max_chunk.compare_exchange_weak(prev, len)) {
        }
        for (std::size_t i = b; i < e; ++i) seen[i]++;
      });
      for (std::size_t i = 0; i < n; ++i) CHECK(seen[i] == 1);
      CHECK(max_chunk <= 64);
    }
  }
}

TEST_CASE("an exception in a chunk is rethrown to the caller and the pool keeps working") {
  ThreadPool pool(2);
  CHECK_THROWS_AS(pool.parallel_for(100, 10,
                                    [](std::size_t b, std::size_t e) {
                                      if (b <= 50 && 50 < e) throw std::runtime_error("chunk failed");
                                    }),
                  std::runtime_error);
  std::atomic<int> count{0};
  pool.parallel_for(100, 10, [&](std::size_t b, std::size_t e) { count += static_cast<int>(e - b); });
  CHECK(count == 100);
}

TEST_CASE("several callers can submit at once") {
  ThreadPool pool(2);
  std::atomic<long> total{0};
  std::vector<std::thread> callers;
  callers.reserve(6);
  for (int c = 0; c < 6; ++c)
    callers.emplace_back([&] {
      for (int rep = 0; rep < 20; ++rep)
        pool.parallel_for(500, 16, [&](std::size_t b, std::size_t e) { total += static_cast<long>(e - b); });
    });
  for (auto& t : callers) t.join();
  CHECK(total == 6L * 20 * 500);
  CHECK(pool.queued() == 0);
}

TEST_CASE("a small job is not stuck behind a large one: jobs share the workers round-robin") {
  ThreadPool pool(1);
  std::atomic<bool> small_done{false};
  std::atomic<int> big_chunks_after_small{0};
  std::atomic<bool> big_started{false};
  std::thread big([&] {
    pool.parallel_for(200, 1, [&](std::size_t, std::size_t) {
      big_started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      if (small_done) big_chunks_after_small++;
    });
  });
  while (!big_started) std::this_thread::yield();
  pool.parallel_for(1, 1, [&](std::size_t, std::size_t) { small_done = true; });
  big.join();
  // With first-in-first-out scheduling every chunk of the big job would run before the small one.
  CHECK(big_chunks_after_small > 150);
}

namespace {

// Waits (politely) until `condition` holds.
template <class F>
void wait_until(F condition) {
  while (!condition()) std::this_thread::sleep_for(std::chrono::microseconds(50));
}

}  // namespace

TEST_CASE("a single point waits for one grain of each tenant ahead, not for a tenant's queued jobs") {
  // One worker. Tenant "flood" has six large jobs queued (one grain each in turn, each grain one
  // item); tenant "other" then submits one item. The worker is held inside flood's first grain
  // until both are queued, so the order is fixed: the rotation is [flood, other] and other's item
  // runs after at most two of flood's grains (the held one and one more). Queued per job instead
  // of per tenant, it would wait for a grain of each of flood's six jobs.
  ThreadPool pool(1);
  std::atomic<bool> release{false};
  std::atomic<int> flood_grains{0};
  std::vector<std::thread> flood;
  for (int j = 0; j < 6; ++j)
    flood.emplace_back([&] {
      JobOptions options;
      options.tenant = "flood";
      pool.parallel_for(
          200, 1,
          [&](std::size_t, std::size_t) {
            wait_until([&] { return release.load(); });
            ++flood_grains;
          },
          options);
    });
  // the worker holds one flood grain and all six jobs are queued (the held one's job is put back)
  wait_until([&] { return pool.queued() == 6; });
  std::atomic<int> flood_grains_before_other{-1};
  std::thread other([&] {
    JobOptions options;
    options.tenant = "other";
    pool.parallel_for(
        1, 1, [&](std::size_t, std::size_t) { flood_grains_before_other = flood_grains.load(); }, options);
  });
  wait_until([&] { return pool.queued() == 7; });
  release = true;
  other.join();
  for (auto& t : flood) t.join();
  CHECK(flood_grains_before_other.load() >= 1);
  CHECK(flood_grains_before_other.load() <= 2);
  CHECK(flood_grains == 6 * 200);
}

TEST_CASE("grains are sized by time: a single point does not wait for a batch's large grains") {
  // One worker, grains aiming at 1 ms; the batch lets the pool take up to 50,000 items at once.
  // Each item sleeps at least 20 us, so a grain sized by time holds at most 1 ms / 20 us = 50 items
  // and the single waits for the rest of the grain in progress and one more: fewer than a few
  // hundred of the batch's items. With grains of the caller's maximum it would wait for tens of
  // thousands. The batch is then cancelled, which also shows that its grains not started are dropped.
  ThreadPool pool(1, std::chrono::milliseconds(1));
  std::atomic<std::size_t> items{0};
  std::atomic<bool> stop{false};
  std::size_t ran = 0;
  std::thread batch([&] {
    JobOptions options;
    options.cancelled = [&] { return stop.load(); };
    ran = pool.parallel_for(
        100000, 50000,
        [&](std::size_t b, std::size_t e) {
          for (std::size_t i = b; i < e; ++i) {
            std::this_thread::sleep_for(std::chrono::microseconds(20));
            ++items;
          }
        },
        options);
  });
  wait_until([&] { return items.load() > 0 && pool.queued() == 1; });
  const std::size_t items_at_submission = items.load();
  std::size_t items_at_single = 0;
  pool.parallel_for(1, 1, [&](std::size_t, std::size_t) { items_at_single = items.load(); });
  stop = true;
  batch.join();
  INFO("batch items run while the single waited: " << items_at_single - items_at_submission);
  CHECK(items_at_single - items_at_submission <= 200);
  CHECK(ran < 100000);
  CHECK(ran == items.load());
}

TEST_CASE("a cancelled job drops the grains not started; the pool keeps working") {
  for (unsigned threads : {1u, 2u}) {
    ThreadPool pool(threads);
    std::vector<std::atomic<int>> seen(5000);
    std::atomic<bool> cancel{false};
    std::atomic<int> grains_after_cancel{0};
    JobOptions options;
    options.cancelled = [&] { return cancel.load(); };
    const std::size_t ran = pool.parallel_for(
        seen.size(), 1,
        [&](std::size_t b, std::size_t) {
          if (cancel) ++grains_after_cancel;
          seen[b]++;
          if (b == 100) cancel = true;
        },
        options);
    std::size_t visited = 0;
    for (auto& s : seen) {
      CHECK(s <= 1);
      visited += static_cast<std::size_t>(s.load());
    }
    CHECK(ran == visited);
    CHECK(ran < seen.size());
    // grains claimed before the cancellation was seen: at most one per other worker
    CHECK(grains_after_cancel <= static_cast<int>(threads) - 1);
    CHECK(pool.queued() == 0);
    std::atomic<int> count{0};
    CHECK(pool.parallel_for(100, 10,
                            [&](std::size_t b, std::size_t e) { count += static_cast<int>(e - b); }) == 100);
    CHECK(count == 100);
  }
}

namespace {

// A cgroup file system of our own under the test's working directory: `files` path -> content.
std::string fake_cgroup(const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& files) {
  const std::filesystem::path root = std::filesystem::current_path() / ("cgroup_" + name);
  std::filesystem::remove_all(root);
  for (const auto& [path, content] : files) {
    std::filesystem::create_directories((root / path).parent_path());
    std::ofstream(root / path) << content;
  }
  return root.string();
}

}  // namespace

TEST_CASE("0 threads: the CPUs of the cgroup's quota (v2 cpu.max, v1 cfs), else the hardware's") {
  using footpoint::cpus_of_cgroup;
  // cgroup v2: quota and period in microseconds, rounded up; "max" is no quota
  CHECK(cpus_of_cgroup(fake_cgroup("v2_two", {{"cpu.max", "200000 100000\n"}}), 16) == 2);
  CHECK(cpus_of_cgroup(fake_cgroup("v2_half", {{"cpu.max", "150000 100000\n"}}), 16) == 2);
  CHECK(cpus_of_cgroup(fake_cgroup("v2_tenth", {{"cpu.max", "10000 100000\n"}}), 16) == 1);
  CHECK(cpus_of_cgroup(fake_cgroup("v2_max", {{"cpu.max", "max 100000\n"}}), 16) == 16);
  // never more than the hardware
  CHECK(cpus_of_cgroup(fake_cgroup("v2_many", {{"cpu.max", "6400000 100000\n"}}), 8) == 8);
  // cgroup v1, under cpu/ or cpu,cpuacct/; -1 is no quota
  CHECK(cpus_of_cgroup(
            fake_cgroup("v1", {{"cpu/cpu.cfs_quota_us", "300000\n"}, {"cpu/cpu.cfs_period_us", "100000\n"}}),
            16) == 3);
  CHECK(cpus_of_cgroup(fake_cgroup("v1_acct", {{"cpu,cpuacct/cpu.cfs_quota_us", "50000\n"},
                                               {"cpu,cpuacct/cpu.cfs_period_us", "100000\n"}}),
                       16) == 1);
  CHECK(cpus_of_cgroup(
            fake_cgroup("v1_none", {{"cpu/cpu.cfs_quota_us", "-1\n"}, {"cpu/cpu.cfs_period_us", "100000\n"}}),
            16) == 16);
  // no cgroup files at all; unreadable content
  CHECK(cpus_of_cgroup(fake_cgroup("none", {}), 12) == 12);
  CHECK(cpus_of_cgroup(fake_cgroup("garbage", {{"cpu.max", "lots\n"}}), 12) == 12);
  CHECK(cpus_of_cgroup(fake_cgroup("none", {}), 0) == 1);
  for (const char* name :
       {"v2_two", "v2_half", "v2_tenth", "v2_max", "v2_many", "v1", "v1_acct", "v1_none", "none", "garbage"})
    std::filesystem::remove_all(std::filesystem::current_path() / (std::string("cgroup_") + name));
  // the pool of 0 threads has default_threads() workers, at least one
  ThreadPool pool(0);
  CHECK(pool.size() == footpoint::default_threads());
  CHECK(pool.size() >= 1);
}
