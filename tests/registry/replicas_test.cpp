// Two footpoint-server processes on one real Redis: an id posted to one is answered by the other
// bit for bit, a deletion reaches the other within a second, concurrent misses compile once, an
// entry whose hash is not its id is refused, use on any replica keeps an entry from expiring.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "compiled/compiled_geometry.hpp"
#include "compiled/sha256.hpp"
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

TEST_CASE("the registry records the key that posted a geometry; old records read as posted by nobody") {
  Redis redis;
  const std::string dir = make_temp_dir();
  const std::string keys = dir + "/keys";
  {
    std::ofstream out(keys);
    out << "alice project,write " << sha256_hex("alice-secret") << "\nbob project,write "
        << sha256_hex("bob-secret") << "\ncarol delete " << sha256_hex("carol-secret") << "\n";
  }
  Server a(replica_env(redis, {{"FOOTPOINT_API_KEYS", keys}})),
      b(replica_env(redis, {{"FOOTPOINT_API_KEYS", keys}}));
  auto as = [](const Server& s, const char* secret) {
    auto c = s.client();
    c->set_bearer_token_auth(secret);
    return c;
  };
  auto alice = as(a, "alice-secret"), bob_on_b = as(b, "bob-secret"), carol_on_b = as(b, "carol-secret");

  const Answer posted = send(*alice, "POST", "/v1/geometries", surface("u*v-v"));
  REQUIRE(posted.status == 201);
  const std::string id = posted.body["geometry_id"];
  // The record: the poster's line, then the canonical text whose hash is still the id.
  const std::string record = redis.command({"GET", "footpoint:v1:geometry:" + id}).str;
  REQUIRE(record.rfind("posted_by=alice\n", 0) == 0);
  CHECK(sha256_hex(record.substr(record.find('\n') + 1)).substr(0, 32) == id);
  // Replica b loads it from Redis and names alice; bob posting it again changes nothing.
  Answer info = send(*bob_on_b, "GET", "/v1/geometries/" + id);
  REQUIRE(info.status == 200);
  CHECK(info.body["posted_by"] == "alice");
  CHECK(send(*bob_on_b, "POST", "/v1/geometries", surface("u*v-v")).status == 200);
  CHECK(redis.command({"GET", "footpoint:v1:geometry:" + id}).str == record);
  const Answer listed = send(*bob_on_b, "GET", "/v1/geometries");
  REQUIRE(listed.body["geometries"].size() == 1);
  CHECK(listed.body["geometries"][0]["posted_by"] == "alice");

  // A record of the earlier format (the canonical text alone) is read, posted by nobody.
  GeometryDefinition old;
  old.type = GeometryType::parametric_surface;
  old.formulas = {{"x", "u"}, {"y", "v"}, {"z", "u-v^3"}};
  old.domain = {{"u", {-2.0, 2.0}}, {"v", {-2.0, 2.0}}};
  redis.command({"SET", "footpoint:v1:geometry:" + old.id(), old.canonical()});
  info = send(*bob_on_b, "GET", "/v1/geometries/" + old.id());
  REQUIRE(info.status == 200);
  CHECK(info.body["posted_by"].is_null());

  // Deleted on replica a (which never loaded it): the audit line names the deleter and the
  // poster, read from the record in the deleting transaction.
  const Answer third = send(*as(b, "bob-secret"), "POST", "/v1/geometries", surface("u+v^2"));
  REQUIRE(third.status == 201);
  const std::string third_id = third.body["geometry_id"];
  auto carol_on_a = as(a, "carol-secret");
  REQUIRE(send(*carol_on_a, "DELETE", "/v1/geometries/" + third_id).status == 204);
  CHECK(eventually([&] {
    const std::string log = a.log();
    const auto at = log.find("\"msg\":\"geometry deleted\"");
    if (at == std::string::npos) return false;
    const std::string line = log.substr(at, log.find('\n', at) - at);
    return line.find("\"key\":\"carol\"") != std::string::npos &&
           line.find("\"geometry_id\":\"" + third_id + "\"") != std::string::npos &&
           line.find("\"posted_by\":\"bob\"") != std::string::npos;
  }));
  CHECK(a.log().find("\"level\":\"info\"") != std::string::npos);
  // Deleted where it is held: the poster from the cache entry.
  REQUIRE(send(*carol_on_b, "DELETE", "/v1/geometries/" + id).status == 204);
  CHECK(eventually([&] {
    return b.log().find("\"key\":\"carol\",\"geometry_id\":\"" + id +
                        "\",\"held\":true,\"posted_by\":\"alice\"") != std::string::npos;
  }));
  std::filesystem::remove_all(dir);
}
