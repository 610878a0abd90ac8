// Two footpoint-server processes on one real Redis: an id posted to one is answered by the other
// bit for bit, a deletion reaches the other within a second, concurrent misses compile once, an
// entry whose hash is not its id is refused, use on any replica keeps an entry from expiring.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "registry_support.hpp"

using namespace footpoint;
using namespace footpoint::registry_testing;

TEST_CASE("an id posted on one replica is answered by another, bit for bit, until it is deleted") {
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  auto ca = a.client(), cb = b.client();

  const Answer posted = send(*ca, "POST", "/v1/geometries", surface("u*v+sin(u)"));
  REQUIRE(posted.status == 201);
  CHECK(posted.body["registry"] == "stored");
  const std::string id = posted.body["geometry_id"];
  const std::string path = "/v1/geometries/" + id;
  CHECK(redis.command({"EXISTS", "footpoint:v1:geometry:" + id}).integer == 1);

  const Answer on_b = send(*cb, "POST", path + "/project", kPoints);
  REQUIRE(on_b.status == 200);
  const Answer on_a = send(*ca, "POST", path + "/project", kPoints);
  REQUIRE(on_a.status == 200);
  CHECK(on_b.body["results"].dump() == on_a.body["results"].dump());  // shortest round-trip numbers
  CHECK(metric(*cb, "footpoint_registry_lookups_total{result=\"hit\"}") == 1);
  const Answer info = send(*cb, "GET", path);
  REQUIRE(info.status == 200);
  CHECK(info.body["definition"]["z"] == "u*v+sin(u)");
  // A second post of the same definition (another replica) writes the same bytes again.
  const Answer again = send(*cb, "POST", "/v1/geometries", surface("u*v + sin(u)"));
  CHECK(again.status == 200);
  CHECK(again.body["registry"] == "stored");

  REQUIRE(send(*ca, "DELETE", path).status == 204);
  const auto deleted_at = Clock::now();
  CHECK(redis.command({"EXISTS", "footpoint:v1:geometry:" + id}).integer == 0);
  CHECK(eventually([&] { return send(*cb, "POST", path + "/project", kPoints).status == 404; }, 1000ms));
  CHECK(Clock::now() - deleted_at < 1s);
  CHECK(send(*cb, "GET", path).body["error"]["code"] == "geometry_not_found");
  CHECK(metric(*cb, "footpoint_registry_invalidations_total{source=\"message\"}") == 1);
  CHECK(send(*cb, "DELETE", path).status == 404);
  CHECK(a.stop() == 0);
  CHECK(b.stop() == 0);
}

TEST_CASE("eight threads asking one replica for an id posted on another compile it once") {
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  const Answer posted = send(*a.client(), "POST", "/v1/geometries", surface("u^3-3*u*v^2"));
  REQUIRE(posted.status == 201);
  const std::string path = "/v1/geometries/" + std::string(posted.body["geometry_id"]) + "/project";
  auto cb = b.client();
  const double compiled_before = metric(*cb, "footpoint_geometry_compilations_total{result=\"ok\"}");

  std::atomic<int> ok{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&] {
      auto c = b.client();
      if (auto r = c->Post(path.c_str(), kPoints, "application/json"); r && r->status == 200) ++ok;
    });
  for (auto& t : threads) t.join();
  CHECK(ok == 8);
  CHECK(metric(*cb, "footpoint_geometry_compilations_total{result=\"ok\"}") - compiled_before == 1);
  CHECK(metric(*cb, "footpoint_registry_lookups_total{result=\"hit\"}") == 1);
}

TEST_CASE(
    "an entry whose content hash is not its id is refused, logged and counted, and a re-post repairs it") {
  const std::string cli = redis_cli_path();
  REQUIRE_MESSAGE(!cli.empty(), "redis-cli is installed with redis-server");
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  GeometryDefinition wanted, other;
  wanted.type = other.type = GeometryType::parametric_surface;
  wanted.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u^2+v^2"}};
  other.formulas = {{"x", "u"}, {"y", "v"}, {"z", "0"}};
  wanted.domain = other.domain = {{"u", {-2.0, 2.0}}, {"v", {-2.0, 2.0}}};
  const std::string id = wanted.id();
  // Another (valid, canonical) definition under this id, as a tampering client would write it.
  const std::string command = "'" + cli + "' -h 127.0.0.1 -p " + std::to_string(redis.port()) +
                              " --no-auth-warning -a " + redis.password() +
                              " SET footpoint:v1:geometry:" + id + " '" + other.canonical() + "' > /dev/null";
  REQUIRE(std::system(command.c_str()) == 0);

  auto cb = b.client();
  const Answer refused = send(*cb, "POST", "/v1/geometries/" + id + "/project", kPoints);
  CHECK(refused.status == 404);
  CHECK(refused.body["error"]["code"] == "geometry_not_found");
  CHECK(metric(*cb, "footpoint_registry_rejected_entries_total") == 1);
  CHECK(metric(*cb, "footpoint_geometry_compilations_total{result=\"ok\"}") == 0);  // never compiled
  CHECK(eventually([&] { return b.log().find("\"msg\":\"registry entry refused\"") != std::string::npos; }));
  CHECK(b.log().find("its content hash is not its id") != std::string::npos);

  // Not canonical either: refused the same way.
  redis.command({"SET", "footpoint:v1:geometry:" + std::string(32, 'a'), "footpoint/1;type=x"});
  CHECK(send(*cb, "POST", "/v1/geometries/" + std::string(32, 'a') + "/project", kPoints).status == 404);
  CHECK(metric(*cb, "footpoint_registry_rejected_entries_total") == 2);

  const std::string body =
      R"({"type":"parametric_surface","x":"u","y":"v","z":"u^2+v^2","domain":{"u":[-2,2],"v":[-2,2]}})";
  const Answer posted = send(*a.client(), "POST", "/v1/geometries", body);
  CHECK(posted.body["geometry_id"] == id);
  CHECK(posted.body["registry"] == "stored");
  const Answer repaired = send(*cb, "POST", "/v1/geometries/" + id + "/project", R"({"point":[0,0,2]})");
  REQUIRE(repaired.status == 200);
  // The paraboloid (nearest at u^2 + v^2 = 3/2, distance sqrt(7/4)), not the plane z = 0 (distance 2).
  CHECK(repaired.body["result"]["distance"].get<double>() == doctest::Approx(std::sqrt(1.75)).epsilon(1e-12));
}

TEST_CASE("use on a replica refreshes the TTL; an unused entry expires") {
  Redis redis;
  Server a(replica_env(redis, {{"FOOTPOINT_REGISTRY_TTL_S", "1"}}));
  auto ca = a.client();
  const Answer posted = send(*ca, "POST", "/v1/geometries", surface("u-v"));
  REQUIRE(posted.body["registry"] == "stored");
  const std::string key = "footpoint:v1:geometry:" + std::string(posted.body["geometry_id"]);
  // Level-1 hits only, for twice the TTL: the monitor keeps refreshing the entry.
  const auto until = Clock::now() + 2s;
  while (Clock::now() < until) {
    REQUIRE(
        send(*ca, "POST", "/v1/geometries/" + std::string(posted.body["geometry_id"]) + "/project", kPoints)
            .status == 200);
    std::this_thread::sleep_for(50ms);
  }
  CHECK(redis.command({"EXISTS", key}).integer == 1);
  CHECK(eventually([&] { return redis.command({"EXISTS", key}).integer == 0; }, 3000ms));
}

TEST_CASE("without a registry URL the server is one process: the POST says registry off") {
  Server alone({});
  auto c = alone.client();
  const Answer posted = send(*c, "POST", "/v1/geometries", surface("u+v"));
  CHECK(posted.status == 201);
  CHECK(posted.body["registry"] == "off");
  CHECK(metric(*c, "footpoint_registry_up") == 0);
  auto r = c->Get("/metrics");
  CHECK(r->body.find("footpoint_registry_") == std::string::npos);
}
