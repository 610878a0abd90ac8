// The core's thread pool: every index runs exactly once, chunks honour their bounds, exceptions
// reach the caller, and concurrent callers share the pool safely.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
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
