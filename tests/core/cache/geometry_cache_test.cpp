// core/cache/geometry_cache: LRU by count and by bytes, statistics, one compilation per id under
// concurrency, failed compilations leave nothing behind. Real geometries throughout.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cache/geometry_cache.hpp"

using namespace footpoint;

namespace {

GeometryDefinition curve(int k) {
  GeometryDefinition d;
  d.type = GeometryType::parametric_curve;
  d.formulas = {{"x", "t"}, {"y", "t^2+" + std::to_string(k)}};
  d.domain = {{"t", {0.0, 1.0}}};
  return d;
}

GeometryDefinition surface(const std::string& z) {
  GeometryDefinition d;
  d.type = GeometryType::parametric_surface;
  d.formulas = {{"x", "u"}, {"y", "v"}, {"z", z}};
  d.domain = {{"u", {-1.0, 1.0}}, {"v", {-1.0, 1.0}}};
  return d;
}

}  // namespace

TEST_CASE("the cache evicts the least recently used beyond its entry count") {
  GeometryCache cache({3, std::size_t{1} << 30});
  std::vector<std::string> ids;
  for (int k = 0; k < 3; ++k) {
    const auto r = cache.get_or_compile(curve(k));
    CHECK(r.compiled);
    CHECK(r.compile_time.count() > 0.0);
    ids.push_back(r.geometry->id());
  }
  CHECK(cache.find(ids[0]) != nullptr);  // 0 becomes the most recent; 1 is now the oldest
  const auto again = cache.get_or_compile(curve(2));
  CHECK_FALSE(again.compiled);
  cache.get_or_compile(curve(3));  // evicts 1
  CHECK(cache.find(ids[1]) == nullptr);
  CHECK(cache.find(ids[0]) != nullptr);
  CHECK(cache.find(ids[2]) != nullptr);
  const auto s = cache.stats();
  CHECK(s.size == 3);
  CHECK(s.evictions == 1);
  CHECK(s.compilations == 4);
  CHECK(s.hits == 4);    // find(0), get(2), find(0), find(2)
  CHECK(s.misses == 5);  // four compilations and find(1)
  CHECK(cache.entry_stats(ids[0])->hits == 2);
  CHECK(cache.erase(ids[0]));
  CHECK_FALSE(cache.erase(ids[0]));
  CHECK(cache.stats().size == 2);
}

TEST_CASE("the cache evicts by bytes and never keeps a geometry larger than its budget") {
  GeometryCache probe;
  const std::size_t a = probe.get_or_compile(surface("u*v")).geometry->memory_bytes();
  const std::size_t b = probe.get_or_compile(surface("u^2-v^2")).geometry->memory_bytes();
  REQUIRE(a > 0);
  REQUIRE(b > 0);
  GeometryCache cache({100, a + b - 1});
  const auto first = cache.get_or_compile(surface("u*v")).geometry;
  cache.get_or_compile(surface("u^2-v^2"));  // a + b > budget: the first goes
  CHECK(cache.find(first->id()) == nullptr);
  CHECK(cache.stats().size == 1);
  CHECK(cache.stats().bytes == b);
  CHECK(cache.stats().evictions == 1);
  CHECK(first->memory_bytes() == a);  // an evicted geometry stays valid for its holders

  GeometryCache tiny({100, 1});
  const auto big = tiny.get_or_compile(surface("u*v"));
  CHECK(big.geometry != nullptr);  // compiled and returned...
  CHECK(tiny.stats().size == 0);   // ...but not kept
  CHECK(tiny.stats().bytes == 0);
}

TEST_CASE("concurrent requests for one new id compile it once and share it") {
  GeometryCache cache;
  const GeometryDefinition def = surface("sin(3*u)*cos(2*v)+u^3");
  constexpr int kThreads = 8;
  std::vector<std::shared_ptr<const CompiledGeometry>> got(kThreads);
  std::atomic<int> compiled{0}, ready{0};
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int i = 0; i < kThreads; ++i)
    threads.emplace_back([&, i] {
      ++ready;
      while (ready.load() < kThreads) std::this_thread::yield();
      const auto r = cache.get_or_compile(def);
      compiled += r.compiled;
      got[i] = r.geometry;
    });
  for (auto& t : threads) t.join();
  CHECK(compiled.load() == 1);
  CHECK(cache.stats().compilations == 1);
  CHECK(cache.stats().misses == 1);
  CHECK(cache.stats().hits == kThreads - 1);
  for (const auto& g : got) CHECK(g.get() == got[0].get());
}

TEST_CASE("a definition that does not compile leaves the cache as it was") {
  GeometryCache cache;
  const auto good = cache.get_or_compile(surface("u*v")).geometry;
  const auto before = cache.stats();
  CHECK_THROWS_AS(cache.get_or_compile(surface("u*(v")), GeometryError);
  CHECK_THROWS_AS(cache.get_or_compile(surface("u*w")), GeometryError);
  const auto after = cache.stats();
  CHECK(after.size == before.size);
  CHECK(after.bytes == before.bytes);
  CHECK(after.failed_compilations == 2);
  CHECK(cache.find(good->id()) == good);
  // Many threads failing on the same bad definition at once all get the error.
  std::atomic<int> errors{0};
  std::vector<std::thread> threads;
  threads.reserve(6);
  for (int i = 0; i < 6; ++i)
    threads.emplace_back([&] {
      try {
        cache.get_or_compile(surface("sin(u"));
      } catch (const GeometryError& e) {
        errors += std::string(e.code) == "formula_syntax";
      }
    });
  for (auto& t : threads) t.join();
  CHECK(errors.load() == 6);
  CHECK(cache.stats().size == 1);
}

TEST_CASE("the cache stays consistent under concurrent mixed use") {
  GeometryCache cache({8, std::size_t{1} << 30});
  std::vector<std::thread> threads;
  threads.reserve(4);
  std::atomic<int> wrong{0};
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 60; ++i) {
        const int k = (i * 7 + t * 3) % 20;
        const auto r = cache.get_or_compile(curve(k));
        if (r.geometry->definition().formulas[1].expression != "t^2+" + std::to_string(k)) ++wrong;
        if (i % 5 == 0) cache.erase(r.geometry->id());
        if (const auto f = cache.find(curve((k + 1) % 20).id()); f && f->id() != curve((k + 1) % 20).id())
          ++wrong;
      }
    });
  for (auto& th : threads) th.join();
  CHECK(wrong.load() == 0);
  const auto s = cache.stats();
  CHECK(s.size <= 8);
  std::set<std::string> ids;
  for (int k = 0; k < 20; ++k)
    if (cache.find(curve(k).id())) ids.insert(curve(k).id());
  CHECK(ids.size() == cache.stats().size);
}

TEST_CASE("a geometry over max_geometry_bytes is refused with its size and not kept") {
  // The size each geometry reaches, from a cache without the bound.
  GeometryCache unbounded({16, std::size_t{1} << 30});
  const auto small = unbounded.get_or_compile(curve(1)).geometry->memory_bytes();
  const auto large = unbounded.get_or_compile(surface("sin(3*u)*cos(3*v)")).geometry->memory_bytes();
  REQUIRE(small < large);

  GeometryCache cache({16, std::size_t{1} << 30, (small + large) / 2});
  CHECK(cache.get_or_compile(curve(1)).compiled);
  try {
    cache.get_or_compile(surface("sin(3*u)*cos(3*v)"));
    FAIL("a geometry over the bound was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.code == "geometry_too_large");
    CHECK(std::string(e.what()).find(std::to_string(large) + " bytes") != std::string::npos);
    CHECK(std::string(e.what()).find(std::to_string((small + large) / 2)) != std::string::npos);
  }
  const auto stats = cache.stats();
  CHECK(stats.size == 1);
  CHECK(stats.bytes == small);
  CHECK(stats.failed_compilations == 1);
  CHECK(cache.find(curve(1).id()) != nullptr);
  // Refused again, not remembered as held.
  CHECK_THROWS_AS(cache.get_or_compile(surface("sin(3*u)*cos(3*v)")), GeometryError);
  CHECK(cache.stats().size == 1);
}

namespace {

bool held_by(GeometryCache& cache, const std::string& id, const std::string& owner) {
  const auto entry = cache.entry_stats(id);
  return entry && entry->owner == owner;
}

}  // namespace

TEST_CASE("one owner's flood evicts its own entries beyond its share, not another owner's") {
  GeometryCacheOptions options{4, std::size_t{1} << 30};
  options.share = 0.5;  // two of the four entries once someone else holds one
  GeometryCache cache(options);
  std::vector<std::string> a;
  for (int k = 0; k < 4; ++k) a.push_back(cache.get_or_compile(curve(k), {}, "A").geometry->id());
  // Alone, A fills the whole cache.
  for (const auto& id : a) CHECK(held_by(cache, id, "A"));
  // B's post evicts A's least recently used entry: A held more than its share, B nothing.
  const std::string b = cache.get_or_compile(curve(100), {}, "B").geometry->id();
  CHECK(held_by(cache, b, "B"));
  CHECK(cache.entry_stats(a[0]) == std::nullopt);
  // A's flood: each new entry of A evicts A's own least recently used one, never B's.
  for (int k = 4; k < 40; ++k) {
    const std::string id = cache.get_or_compile(curve(k), {}, "A").geometry->id();
    CHECK(held_by(cache, id, "A"));
    CHECK(held_by(cache, b, "B"));
  }
  const auto ids = cache.ids();
  CHECK(ids.size() == 4);
  CHECK(std::count_if(ids.begin(), ids.end(),
                      [&](const std::string& id) { return held_by(cache, id, "A"); }) == 3);
  // An entry already held keeps its owner whoever asks for it.
  CHECK_FALSE(cache.get_or_compile(curve(100), {}, "A").compiled);
  CHECK(held_by(cache, b, "B"));
  // Without a share (1: plain LRU), the same flood evicts B's entry.
  GeometryCache plain({4, std::size_t{1} << 30});
  const std::string b2 = plain.get_or_compile(curve(100), {}, "B").geometry->id();
  for (int k = 0; k < 4; ++k) plain.get_or_compile(curve(k), {}, "A");
  CHECK(plain.entry_stats(b2) == std::nullopt);
}

TEST_CASE("the share bounds bytes, and a geometry that only fits past its owner's share is refused") {
  // Five curves whose compiled forms hold the same bytes s (the most common size of 40).
  GeometryCache probe({64, std::size_t{1} << 30});
  std::map<std::size_t, std::vector<int>> by_size;
  for (int k = 0; k < 40; ++k) by_size[probe.get_or_compile(curve(k)).geometry->memory_bytes()].push_back(k);
  const auto most = std::max_element(by_size.begin(), by_size.end(), [](const auto& x, const auto& y) {
    return x.second.size() < y.second.size();
  });
  REQUIRE(most->second.size() >= 5);
  const std::size_t s = most->first;
  const auto curve = [&](int i) { return ::curve(most->second[static_cast<std::size_t>(i)]); };
  GeometryCacheOptions options{100, 3 * s};
  options.share = 0.3;  // less than one geometry's bytes
  GeometryCache cache(options);
  // Alone, B may fill the cache.
  const std::string b = cache.get_or_compile(curve(0), {}, "B").geometry->id();
  // A fits beside B without evicting anything, twice; its third evicts its own oldest.
  const std::string a1 = cache.get_or_compile(curve(1), {}, "A").geometry->id();
  const std::string a2 = cache.get_or_compile(curve(2), {}, "A").geometry->id();
  const std::string a3 = cache.get_or_compile(curve(3), {}, "A").geometry->id();
  CHECK(held_by(cache, b, "B"));
  CHECK(cache.entry_stats(a1) == std::nullopt);
  CHECK(held_by(cache, a2, "A"));
  CHECK(held_by(cache, a3, "A"));
  CHECK(cache.stats().bytes == 3 * s);
  // C holds nothing, and its geometry could only be kept by evicting A's or B's beyond C's share.
  try {
    cache.get_or_compile(curve(4), {}, "C");
    FAIL("C's geometry was kept past its share");
  } catch (const GeometryError& e) {
    CHECK(e.code == "cache_share_exceeded");
    CHECK(std::string(e.what()).find(std::to_string(s) + " bytes") != std::string::npos);
  }
  CHECK(cache.stats().size == 3);
  CHECK(held_by(cache, b, "B"));
  // Once B's entry is deleted, C's geometry fits beside A's.
  CHECK(cache.erase(b));
  CHECK(held_by(cache, cache.get_or_compile(curve(4), {}, "C").geometry->id(), "C"));
}

TEST_CASE("a lookup's geometry past its owner's share is answered and not kept") {
  GeometryCache probe({16, std::size_t{1} << 30});
  const std::size_t s0 = probe.get_or_compile(curve(0)).geometry->memory_bytes();
  const std::size_t s1 = probe.get_or_compile(curve(1)).geometry->memory_bytes();
  GeometryCacheOptions options{100, s0 + s1 - 1};
  options.share = 0.1;  // less than either geometry
  GeometryCache cache(options);
  const std::string b = cache.get_or_compile(curve(0), {}, "B").geometry->id();
  const auto loaded = cache.get_or_compile(curve(1), {}, "A", false);
  REQUIRE(loaded.geometry != nullptr);
  CHECK(cache.entry_stats(loaded.geometry->id()) == std::nullopt);
  CHECK(held_by(cache, b, "B"));
  CHECK_THROWS_AS(cache.get_or_compile(curve(1), {}, "A"), GeometryError);
}
