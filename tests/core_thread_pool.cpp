// The core's thread pool: every index runs exactly once, chunks honour their bounds, exceptions
// reach the caller, and concurrent callers share the pool safely.
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
                                    [](std::size_t b, std::size_t) {
                                      if (b == 50) throw std::runtime_error("chunk failed");
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
