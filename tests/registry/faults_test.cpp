// The registry's faults against a real redis-server: down (killed), unreachable (connections
// that are never accepted), slow (CLIENT PAUSE), refusing AUTH, restarted empty. In each: no
// request waits past the configured timeout, ids held in level 1 are answered, a POST compiles and
// says the registry did not store it, an id in neither level is 503 registry_unavailable with
// Retry-After, /readyz stays 200; once Redis is back the replicas recover without a restart.
#include <doctest/doctest.h>

#include <string>

#include "registry_support.hpp"

using namespace footpoint::registry_testing;

namespace {

constexpr double kTimeout = 0.2;  // FOOTPOINT_REGISTRY_TIMEOUT_MS of replica_env
// What a request may take beyond the timeout on a loaded 2-core machine (compiling a small
// surface included).
constexpr double kSlack = 0.5;
const std::string kUnknown = "/v1/geometries/" + std::string(32, 'b') + "/project";

std::string project_path(const Answer& posted) {
  return "/v1/geometries/" + posted.body["geometry_id"].get<std::string>() + "/project";
}

// The registry is unavailable to `b` (and `a`): b holds `held` in level 1. Returns the answer to
// a POST on `a` made meanwhile.
Answer check_degraded(Server& a, Server& b, const std::string& held, const std::string& fresh_z) {
  auto ca = a.client(), cb = b.client();
  const Answer hit = send(*cb, "POST", held, kPoints);
  CHECK(hit.status == 200);
  for (int i = 0; i < 3; ++i) {  // the first meets the fault, the next ones the down registry
    const Answer unknown = send(*cb, "POST", kUnknown, kPoints);
    CHECK(unknown.status == 503);
    CHECK(unknown.body["error"]["code"] == "registry_unavailable");
    CHECK(unknown.retry_after == "1");
    CHECK(unknown.seconds < kTimeout + kSlack);
  }
  const Answer posted = send(*ca, "POST", "/v1/geometries", surface(fresh_z));
  CHECK(posted.status == 201);
  CHECK(posted.body["registry"] == "not_stored");
  CHECK(posted.seconds < kTimeout + kSlack);
  const Answer own = send(*ca, "POST", project_path(posted), kPoints);  // held by a, level 1
  CHECK(own.status == 200);
  const Answer deleted = send(*cb, "DELETE", held.substr(0, held.size() - std::string("/project").size()));
  CHECK(deleted.status == 503);  // nothing deleted: it would come back from the registry
  CHECK(deleted.retry_after == "1");
  CHECK(send(*cb, "POST", held, kPoints).status == 200);
  for (Server* s : {&a, &b}) {
    auto c = s->client();
    CHECK(send(*c, "GET", "/readyz").status == 200);
    CHECK(eventually([&] { return metric(*c, "footpoint_registry_up") == 0; }));
  }
  CHECK(metric(*ca, "footpoint_registry_writes_total{result=\"not_stored\"}") >= 1);
  return posted;
}

// Redis is back: both replicas recover by themselves.
void check_recovered(Server& a, Server& b, const std::string& fresh_z) {
  for (Server* s : {&a, &b}) {
    auto c = s->client();
    CHECK(eventually([&] { return metric(*c, "footpoint_registry_up") == 1; }, 5000ms));
  }
  auto ca = a.client(), cb = b.client();
  const Answer posted = send(*ca, "POST", "/v1/geometries", surface(fresh_z));
  CHECK(posted.body["registry"] == "stored");
  CHECK(send(*cb, "POST", project_path(posted), kPoints).status == 200);
  const Answer unknown = send(*cb, "POST", kUnknown, kPoints);
  CHECK(unknown.status == 404);
  CHECK(unknown.body["error"]["code"] == "geometry_not_found");
}

// Posts on a, projects on b: b holds the id in level 1.
std::string shared_geometry(Server& a, Server& b, const std::string& z) {
  const Answer posted = send(*a.client(), "POST", "/v1/geometries", surface(z));
  REQUIRE(posted.body["registry"] == "stored");
  REQUIRE(send(*b.client(), "POST", project_path(posted), kPoints).status == 200);
  return project_path(posted);
}

}  // namespace

TEST_CASE("Redis down, then restarted empty") {
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  const std::string held = shared_geometry(a, b, "u*v");
  redis.kill();
  const Answer during = check_degraded(a, b, held, "u*v+1");
  CHECK(metric(*b.client(), "footpoint_registry_errors_total{kind=\"io\"}") +
            metric(*b.client(), "footpoint_registry_errors_total{kind=\"connect\"}") >=
        1);

  redis.start();  // same port, no data
  check_recovered(a, b, "u*v+2");
  // Posted before the restart: gone from Redis, so dropped by every replica on reconnecting
  // (404, as for any unknown id).
  CHECK(eventually([&] { return send(*b.client(), "POST", held, kPoints).status == 404; }));
  CHECK(metric(*b.client(), "footpoint_registry_invalidations_total{source=\"revalidation\"}") >= 1);
  // Posted on a while Redis was down: stored when it came back, so b answers it.
  CHECK(send(*b.client(), "POST", project_path(during), kPoints).status == 200);
}

TEST_CASE("Redis unreachable: connections are never accepted, then Redis appears on that port") {
  // A listener whose accept queue is full: the kernel drops further SYNs, so connecting hangs
  // until the timeout, as with a host that drops packets.
  // SOCK_CLOEXEC: the servers started below must not inherit (and keep open) the listener.
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int yes = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  REQUIRE(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  REQUIRE(::listen(listener, 0) == 0);
  socklen_t len = sizeof addr;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&addr), &len);
  const int port = ntohs(addr.sin_port);
  const int filler = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  REQUIRE(::connect(filler, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);

  const std::string password = "unreachable-secret-2c";
  std::map<std::string, std::string> env = {
      {"FOOTPOINT_REGISTRY_URL", "redis://127.0.0.1:" + std::to_string(port) + "/0"},
      {"FOOTPOINT_REGISTRY_PASSWORD", password},
      {"FOOTPOINT_REGISTRY_TIMEOUT_MS", "200"}};
  const auto start = Clock::now();
  Server a(env), b(env);
  CHECK(Clock::now() - start < 3s);  // each waits at most about twice the timeout for Redis
  auto ca = a.client(), cb = b.client();
  const Answer posted_on_b = send(*cb, "POST", "/v1/geometries", surface("u+v^2"));
  CHECK(posted_on_b.body["registry"] == "not_stored");
  const Answer during = check_degraded(a, b, project_path(posted_on_b), "u-v^2");
  CHECK(metric(*cb, "footpoint_registry_errors_total{kind=\"timeout\"}") >= 1);

  ::close(filler);
  ::close(listener);
  Redis redis(password, port);
  check_recovered(a, b, "u+v^3");
  // Both posted while unreachable, both stored once Redis was there: each replica answers the other's.
  CHECK(send(*ca, "POST", project_path(posted_on_b), kPoints).status == 200);
  CHECK(send(*cb, "POST", project_path(during), kPoints).status == 200);
}

TEST_CASE("Redis slow: every command waits (CLIENT PAUSE), then answers again") {
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  const std::string held = shared_geometry(a, b, "sin(u)*v");
  redis.command({"CLIENT", "PAUSE", "2500", "ALL"});
  check_degraded(a, b, held, "sin(u)*v+1");
  check_recovered(a, b, "sin(u)*v+2");
  // Still in Redis after the pause: revalidation keeps it, and a new replica can load it.
  CHECK(send(*b.client(), "POST", held, kPoints).status == 200);
  Server c(replica_env(redis));
  CHECK(send(*c.client(), "POST", held, kPoints).status == 200);
}

TEST_CASE("Redis refusing AUTH (the password was rotated), then accepting it again") {
  Redis redis;
  Server a(replica_env(redis)), b(replica_env(redis));
  const std::string held = shared_geometry(a, b, "u^2*v");
  const std::string rotated = "rotated-secret-91d0";
  redis.command({"CONFIG", "SET", "requirepass", rotated});
  redis.command({"CLIENT", "KILL", "TYPE", "normal"}, rotated);
  redis.command({"CLIENT", "KILL", "TYPE", "pubsub"}, rotated);
  check_degraded(a, b, held, "u^2*v+1");
  // The monitor's next attempt meets the new password.
  CHECK(
      eventually([&] { return metric(*b.client(), "footpoint_registry_errors_total{kind=\"auth\"}") >= 1; }));
  CHECK(eventually(
      [&] { return b.log().find("registry refused the command: WRONGPASS") != std::string::npos; }));
  CHECK(b.log().find(redis.password()) == std::string::npos);  // the password is never logged
  CHECK(b.log().find(rotated) == std::string::npos);

  redis.command({"CONFIG", "SET", "requirepass", redis.password()}, rotated);
  check_recovered(a, b, "u^2*v+2");
  CHECK(send(*b.client(), "POST", held, kPoints).status == 200);
}
