// Exposure: API keys with scopes (401, 403, the probes free, /metrics for admin, the keys file read
// again), per-key rate limits in points (429 with Retry-After, another key unaffected) and HTTPS
// with certificates made by the openssl command at test time (TLS 1.2+, plain HTTP refused, the
// certificate swapped by reload() while a request is in flight). Digests are checked against
// FIPS 180-2's examples and the sha256sum command, not against the server's own SHA-256.
#include <doctest/doctest.h>
#include <openssl/ssl.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "access.hpp"
#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {
namespace access_test {

// A temporary directory, removed at the end.
struct TempDir {
  std::string path;
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "footpoint-access.XXXXXX").string();
    REQUIRE(::mkdtemp(pattern.data()) != nullptr);
    path = pattern;
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return path + "/" + name; }
};

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  REQUIRE(out.good());
}

// The output of a shell command (secrets here are letters and digits only).
std::string command_output(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string out;
  char buf[256];
  while (const auto n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  REQUIRE(::pclose(pipe) == 0);
  return out;
}

// The hex SHA-256 of a secret, as the operator makes it (docs/security.md).
std::string sha256sum(const std::string& secret) {
  return command_output("printf %s '" + secret + "' | sha256sum").substr(0, 64);
}

// A self-signed certificate for 127.0.0.1 (P-256 key) made by the openssl command: dir/NAME.crt
// and dir/NAME.key.
void make_certificate(const TempDir& dir, const std::string& name) {
  const std::string command =
      "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 2 "
      "-subj /CN=footpoint-" +
      name + " -addext subjectAltName=IP:127.0.0.1 -keyout " + dir.file(name + ".key") + " -out " +
      dir.file(name + ".crt") + " 2>/dev/null";
  REQUIRE(std::system(command.c_str()) == 0);
}

httplib::Headers bearer(const std::string& secret) { return {{"Authorization", "Bearer " + secret}}; }

const std::string kCurve =
    R"J({"type":"parametric_curve","x":"cos(t)","y":"2*sin(t)","domain":{"t":[0,6]}})J";

// A body of n planar points.
std::string points_body(int n) {
  json points = json::array();
  for (int i = 0; i < n; ++i) points.push_back({1.0 + 0.01 * i, 0.5});
  return json{{"points", points}}.dump();
}

std::string error_code(const httplib::Result& r) {
  return json::parse(r->body)["error"]["code"].get<std::string>();
}

TEST_CASE("exposure flags: TLS files go together, --metrics-key-free alone, rate limit and burst") {
  bool help = false;
  auto no_env = [](const char*) -> const char* { return nullptr; };
  const char* both[] = {"x",  "--tls-cert", "c.pem", "--tls-key=k.pem", "--metrics-key-free", "--rate-limit",
                        "500"};
  ServerConfig c = load_config(7, both, no_env, help);
  CHECK(c.tls_cert == "c.pem");
  CHECK(c.tls_key == "k.pem");
  CHECK(c.metrics_key_free);
  CHECK(c.rate_limit == 500);
  CHECK(c.effective_rate_burst() == c.max_points);  // 0: the larger of the rate and max-points
  const char* burst[] = {"x", "--rate-limit", "200000", "--metrics-key-free=off", "--api-keys", "keys.txt"};
  c = load_config(6, burst, no_env, help);
  CHECK_FALSE(c.metrics_key_free);
  CHECK(c.effective_rate_burst() == 200000);
  CHECK(c.api_keys == "keys.txt");
  const char* cert_only[] = {"x", "--tls-cert", "c.pem"};
  CHECK_THROWS_WITH_AS(load_config(3, cert_only, no_env, help), doctest::Contains("go together"),
                       ConfigError);
  const char* bad_switch[] = {"x", "--metrics-key-free=yes"};
  CHECK_THROWS_AS(load_config(2, bad_switch, no_env, help), ConfigError);
  auto env = [](const char* name) -> const char* {
    return std::string_view(name) == "FOOTPOINT_API_KEYS"           ? "/keys/keys"
           : std::string_view(name) == "FOOTPOINT_METRICS_KEY_FREE" ? "on"
           : std::string_view(name) == "FOOTPOINT_RATE_BURST"       ? "7"
                                                                    : nullptr;
  };
  const char* none[] = {"x"};
  c = load_config(1, none, env, help);
  CHECK(c.api_keys == "/keys/keys");
  CHECK(c.metrics_key_free);
  CHECK(c.rate_burst == 7);
}

TEST_CASE("API keys: SHA-256 of FIPS 180-2's examples and of the sha256sum command") {
  auto hex = [](const std::array<unsigned char, 32>& d) {
    std::string s;
    char buf[3];
    for (const unsigned char c : d) {
      std::snprintf(buf, sizeof buf, "%02x", c);
      s += buf;
    }
    return s;
  };
  CHECK(hex(sha256("abc")) == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(hex(sha256("")) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(hex(sha256("s3cretKey42")) == sha256sum("s3cretKey42"));
}

TEST_CASE("API keys file: keys, comments, and each mistake named with its line") {
  const std::string text = "# name scopes digest\n\nreader project " + sha256sum("r1") +
                           "\r\n  writer  project,write  " + sha256sum("w1") + "\nboss admin " +
                           sha256sum("b1") + "\n";
  const KeyRing ring = KeyRing::parse(text, "keys");
  CHECK(ring.size() == 3);
  const ApiKey* reader = ring.authenticate("r1");
  REQUIRE(reader);
  CHECK(reader->name == "reader");
  CHECK(reader->allows(kScopeProject));
  CHECK_FALSE(reader->allows(kScopeWrite));
  const ApiKey* writer = ring.authenticate("w1");
  REQUIRE(writer);
  CHECK(writer->allows(kScopeWrite));
  CHECK_FALSE(writer->allows(kScopeDelete));
  const ApiKey* boss = ring.authenticate("b1");
  REQUIRE(boss);
  CHECK((boss->allows(kScopeDelete) && boss->allows(kScopeAdmin) && boss->allows(kScopeProject)));
  CHECK(ring.authenticate("r2") == nullptr);
  CHECK(ring.authenticate("") == nullptr);
  CHECK(ring.authenticate(sha256sum("r1")) == nullptr);  // the digest is not the secret

  const std::string d = sha256sum("x");
  auto refused = [](const std::string& file, const std::string& message) {
    CAPTURE(file);
    try {
      KeyRing::parse(file, "keys");
      FAIL("accepted");
    } catch (const KeyFileError& e) {
      CHECK(std::string(e.what()).find(message) != std::string::npos);
    }
  };
  refused("a project\n", "keys line 1: expected NAME SCOPES SHA256HEX");
  refused("\na read " + d + "\n", "keys line 2: unknown scope 'read'");
  refused("a project,,write " + d + "\n", "unknown scope ''");
  refused("a project " + d.substr(1) + "\n", "64 hex digits");
  refused("a project " + d.substr(1) + "g\n", "64 hex digits");
  refused("a project " + d + " extra\n", "expected NAME SCOPES SHA256HEX");
  refused("a\"b project " + d + "\n", "the name must be");
  refused("a project " + d + "\na write " + sha256sum("y") + "\n", "line 2: the name a is given twice");
  refused("a project " + d + "\nb write " + d + "\n", "the secret of b is another key's too");
  CHECK_THROWS_AS(KeyRing::load("/nonexistent/footpoint-keys"), KeyFileError);
}

TEST_CASE("rate limiter: a token bucket of points per key") {
  RateLimiter limiter(100.0, 150.0);
  const auto t0 = RateLimiter::Clock::now();
  using std::chrono::milliseconds;
  CHECK(limiter.take("a", 120, t0).allowed);  // 30 left
  auto d = limiter.take("a", 100, t0);
  CHECK_FALSE(d.allowed);
  CHECK(d.retry_after_s == 1);                                    // 70 points at 100/s
  CHECK(limiter.take("b", 150, t0).allowed);                      // another key's bucket is full
  CHECK(limiter.take("a", 100, t0 + milliseconds(700)).allowed);  // 30 + 70
  CHECK_FALSE(limiter.check("a", t0 + milliseconds(700)).allowed);
  CHECK(limiter.check("a", t0 + milliseconds(711)).allowed);  // 1.1 points again
  d = limiter.take("a", 150, t0 + milliseconds(1200));        // 50 held: 100 more take 1 s
  CHECK_FALSE(d.allowed);
  CHECK(d.retry_after_s == 1);
  CHECK(limiter.take("a", 150, t0 + std::chrono::seconds(60)).allowed);  // full again, never above 150
  CHECK_FALSE(limiter.take("a", 1, t0 + std::chrono::seconds(60)).allowed);
  RateLimiter slow(2.0, 10.0);
  CHECK(slow.take("a", 10, t0).allowed);
  CHECK(slow.take("a", 7, t0).retry_after_s == 4);  // 7 points at 2/s: 3.5 s
}

TEST_CASE("API keys over HTTP: 401, 403 by scope, probes free, /metrics for admin, keys reread") {
  TempDir dir;
  const std::string keys = dir.file("keys");
  write_file(keys, "reader project " + sha256sum("readsecret") + "\nwriter project,write " +
                       sha256sum("writesecret") + "\ndeleter delete " + sha256sum("deletesecret") +
                       "\nboss admin " + sha256sum("bosssecret") + "\n");
  ServerConfig config;
  config.api_keys = keys;
  TestServer s(config);
  auto c = s.client();

  for (const char* probe : {"/healthz", "/readyz", "/openapi.yaml"}) {
    auto r = c->Get(probe);
    REQUIRE(r);
    CHECK_MESSAGE(r->status == 200, probe);
  }
  auto r = c->Get("/v1/methods");
  REQUIRE(r);
  CHECK(r->status == 401);
  CHECK(r->get_header_value("WWW-Authenticate") == R"(Bearer realm="footpoint")");
  CHECK(error_code(r) == "missing_api_key");
  r = c->Get("/v1/methods", {{"Authorization", "Basic cmVhZGVyOnJlYWRzZWNyZXQ="}});
  REQUIRE(r);
  CHECK(r->status == 401);
  r = c->Get("/v1/methods", bearer("readsecreT"));
  REQUIRE(r);
  CHECK(r->status == 401);
  CHECK(error_code(r) == "invalid_api_key");
  CHECK(r->get_header_value("WWW-Authenticate").find(R"(error="invalid_token")") != std::string::npos);
  r = c->Get("/v1/methods", {{"Authorization", "bearer  readsecret "}});
  REQUIRE(r);
  CHECK(r->status == 200);

  // A refused POST's body is not read: the connection closes, the next request opens another.
  r = c->Post("/v1/geometries", bearer("readsecret"), kCurve, "application/json");
  REQUIRE(r);
  CHECK(r->status == 403);
  CHECK(error_code(r) == "insufficient_scope");
  CHECK(r->get_header_value("WWW-Authenticate").find(R"(scope="write")") != std::string::npos);
  r = c->Post("/v1/geometries", bearer("writesecret"), kCurve, "application/json");
  REQUIRE(r);
  REQUIRE(r->status == 201);
  const std::string id = json::parse(r->body)["geometry_id"];
  r = c->Post(("/v1/geometries/" + id + "/project").c_str(), bearer("readsecret"), points_body(3),
              "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  r = c->Post(("/v1/geometries/" + id + "/project").c_str(), bearer("deletesecret"), points_body(3),
              "application/json");
  REQUIRE(r);
  CHECK(r->status == 403);  // delete alone does not project
  r = c->Delete(("/v1/geometries/" + id).c_str(), bearer("writesecret"));
  REQUIRE(r);
  CHECK(r->status == 403);
  r = c->Get(("/v1/geometries/" + id).c_str(), bearer("readsecret"));
  REQUIRE(r);
  CHECK(r->status == 200);  // not deleted
  r = c->Delete(("/v1/geometries/" + id).c_str(), bearer("deletesecret"));
  REQUIRE(r);
  CHECK(r->status == 204);

  r = c->Get("/metrics", bearer("readsecret"));
  REQUIRE(r);
  CHECK(r->status == 403);
  r = c->Get("/metrics", bearer("bosssecret"));
  REQUIRE(r);
  REQUIRE(r->status == 200);
  CHECK(r->body.find(R"(footpoint_api_key_requests_total{key="reader",status="200"} 3)") !=
        std::string::npos);
  CHECK(r->body.find(R"(footpoint_api_key_requests_total{key="writer",status="403"} 1)") !=
        std::string::npos);
  CHECK(r->body.find(R"(footpoint_http_requests_total{route="/v1/methods",status="401"} 3)") !=
        std::string::npos);
  CHECK(r->body.find("secret") == std::string::npos);

  // The file read again: a key removed, one added; a broken file keeps the keys in use.
  write_file(keys, "newcomer project " + sha256sum("newsecret") + "\n");
  CHECK(s.server().reload());
  r = c->Get("/v1/methods", bearer("readsecret"));
  REQUIRE(r);
  CHECK(r->status == 401);
  r = c->Get("/v1/methods", bearer("newsecret"));
  REQUIRE(r);
  CHECK(r->status == 200);
  write_file(keys, "newcomer project nothex\n");
  CHECK_FALSE(s.server().reload());
  r = c->Get("/v1/methods", bearer("newsecret"));
  REQUIRE(r);
  CHECK(r->status == 200);
}

TEST_CASE("API keys: --metrics-key-free, and no keys file means no authentication") {
  TempDir dir;
  write_file(dir.file("keys"), "reader project " + sha256sum("readsecret") + "\n");
  ServerConfig config;
  config.api_keys = dir.file("keys");
  config.metrics_key_free = true;
  TestServer s(config);
  auto c = s.client();
  auto r = c->Get("/metrics");
  REQUIRE(r);
  CHECK(r->status == 200);
  r = c->Get("/v1/methods");
  REQUIRE(r);
  CHECK(r->status == 401);

  TestServer open;
  auto o = open.client();
  r = o->Get("/v1/methods");
  REQUIRE(r);
  CHECK(r->status == 200);
  r = o->Get("/metrics");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK(r->body.find("footpoint_api_key_requests_total") == std::string::npos);

  config.api_keys = dir.file("missing");
  CHECK_THROWS_WITH_AS(HttpServer{test_config(config)}, doctest::Contains("cannot read the keys file"),
                       KeyFileError);
}

TEST_CASE("rate limit: points per key, 429 with Retry-After, another key not slowed") {
  TempDir dir;
  write_file(dir.file("keys"),
             "a project,write " + sha256sum("asecret") + "\nb project " + sha256sum("bsecret") + "\n");
  ServerConfig config;
  config.api_keys = dir.file("keys");
  config.rate_limit = 1;  // one point a second: the test's steps take far less than a second each
  config.rate_burst = 150;
  TestServer s(config);
  auto c = s.client();
  auto r = c->Post("/v1/geometries", bearer("asecret"), kCurve, "application/json");  // 1 point
  REQUIRE(r);
  REQUIRE(r->status == 201);
  const std::string path = "/v1/geometries/" + std::string(json::parse(r->body)["geometry_id"]) + "/project";
  r = c->Post(path.c_str(), bearer("asecret"), points_body(100), "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  r = c->Post(path.c_str(), bearer("asecret"), points_body(100), "application/json");
  REQUIRE(r);
  CHECK(r->status == 429);
  CHECK(error_code(r) == "rate_limited");
  const int retry = std::stoi(r->get_header_value("Retry-After"));
  CHECK(retry >= 45);  // about 51 points missing at one a second
  CHECK(retry <= 52);
  r = c->Post(path.c_str(), bearer("bsecret"), points_body(100), "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  r = c->Post(path.c_str(), bearer("bsecret"), points_body(151), "application/json");
  REQUIRE(r);
  CHECK(r->status == 413);
  CHECK(error_code(r) == "points_over_burst");
  // Spend b's bucket to below one point: then even a request without points is refused before
  // its body is read.
  r = c->Post(path.c_str(), bearer("bsecret"), points_body(50), "application/json");
  REQUIRE(r);
  REQUIRE(r->status == 200);
  r = c->Get("/v1/methods", bearer("bsecret"));
  REQUIRE(r);
  CHECK(r->status == 429);
  CHECK(std::stoi(r->get_header_value("Retry-After")) >= 1);
  r = c->Get("/healthz");
  REQUIRE(r);
  CHECK(r->status == 200);
}

TEST_CASE("isolation: a geometry over --max-geometry-bytes gets 422 and evicts nobody") {
  TestServer s;  // the default bound: a quarter of the 256 MiB cache
  auto c = s.client();
  const std::string kept = create(*c, kCurve);
  const auto bytes_before = s.server().cache().stats().bytes;
  // exp(500 t) over [0, 1]: about 143 MB of search structure, measured on 0.1.0.
  auto r = c->Post("/v1/geometries",
                   R"J({"type":"parametric_curve","x":"exp(t*500)","y":"t","domain":{"t":[0,1]}})J",
                   "application/json");
  REQUIRE(r);
  CHECK(r->status == 422);
  CHECK(error_code(r) == "geometry_too_large");
  CHECK(json::parse(r->body)["error"]["message"].get<std::string>().find("over the limit of 67108864") !=
        std::string::npos);
  CHECK(s.server().cache().stats().bytes == bytes_before);
  r = c->Get(("/v1/geometries/" + kept).c_str());
  REQUIRE(r);
  CHECK(r->status == 200);
}

TEST_CASE("isolation: one key's flood evicts its own geometries beyond --cache-share, not another key's") {
  TempDir dir;
  const std::string keys = dir.file("keys");
  write_file(keys, "flooder project,write " + sha256sum("floodsecret") + "\nquiet project,write " +
                       sha256sum("quietsecret") + "\n");
  ServerConfig config;
  config.api_keys = keys;
  config.cache_entries = 4;
  config.cache_share = 0.5;
  TestServer s(config);
  auto c = s.client();
  const auto post = [&](const std::string& secret, int k) {
    auto r = c->Post("/v1/geometries", bearer(secret),
                     R"J({"type":"parametric_curve","x":"t","y":"t^2+)J" + std::to_string(k) +
                         R"J(","domain":{"t":[0,1]}})J",
                     "application/json");
    REQUIRE(r);
    REQUIRE(r->status == 201);
    return json::parse(r->body)["geometry_id"].get<std::string>();
  };
  const auto posted_by = [&](const std::string& id) {
    auto r = c->Get(("/v1/geometries/" + id).c_str(), bearer("quietsecret"));
    REQUIRE(r);
    return r->status == 200 ? json::parse(r->body)["posted_by"] : json("gone");
  };
  std::vector<std::string> flood;
  for (int k = 0; k < 4; ++k) flood.push_back(post("floodsecret", k));
  for (const auto& id : flood) CHECK(posted_by(id) == "flooder");  // alone, it fills the cache
  const std::string quiet = post("quietsecret", 100);
  CHECK(posted_by(quiet) == "quiet");
  for (int k = 4; k < 20; ++k) {
    const std::string id = post("floodsecret", k);
    CHECK(posted_by(id) == "flooder");
    CHECK(posted_by(quiet) == "quiet");
  }
  const auto stats = s.server().cache().stats();
  CHECK(stats.size == 4);
  auto r = c->Get("/v1/geometries", bearer("quietsecret"));
  REQUIRE(r);
  int quiet_held = 0;
  const json listed = json::parse(r->body);
  for (const auto& g : listed["geometries"]) quiet_held += g["posted_by"] == "quiet" ? 1 : 0;
  CHECK(quiet_held == 1);
}

TEST_CASE("isolation: maximum meshes reserve from --max-inflight-bytes; single points are still answered") {
  ServerConfig config;
  config.max_inflight_bytes = std::size_t{150} << 20;  // one maximum mesh (~108 MB), not two
  config.max_mesh_resolution = 512;
  TestServer s(config);
  auto c = s.client();
  const std::string sphere =
      create(*c, R"J({"type":"parametric_surface","x":"cos(u)*cos(v)","y":"sin(u)*cos(v)","z":"sin(v)",)J"
                 R"J("domain":{"u":[0,6.283185307179586],"v":[-1.5707963267948966,1.5707963267948966]}})J");
  const std::string curve = create(*c, kCurve);
  const std::string mesh_path = "/v1/geometries/" + sphere + "/mesh?resolution=512";
  std::atomic<int> ready{0}, ok{0}, refused{0}, singles_ok{0}, singles{0};
  std::atomic<bool> go{false}, meshes_done{false};
  std::vector<std::string> refusals;
  std::mutex refusals_mutex;
  std::vector<std::thread> threads;
  for (int i = 0; i < 8; ++i)
    threads.emplace_back([&] {
      auto mc = s.client();
      ++ready;
      while (!go.load()) std::this_thread::yield();
      auto r = mc->Get(mesh_path.c_str());
      REQUIRE(r);
      if (r->status == 200) {
        ++ok;
      } else {
        ++refused;
        std::lock_guard lock(refusals_mutex);
        refusals.push_back(std::to_string(r->status) + " " + r->get_header_value("Retry-After") + " " +
                           r->body);
      }
    });
  std::thread single([&] {
    auto sc = s.client();
    while (!go.load()) std::this_thread::yield();
    do {
      auto r = sc->Post(("/v1/geometries/" + curve + "/project").c_str(), R"({"point":[1.5,0.5]})",
                        "application/json");
      ++singles;
      if (r && r->status == 200) ++singles_ok;
    } while (!meshes_done.load());
  });
  while (ready.load() < 8) std::this_thread::yield();
  go = true;
  for (auto& t : threads) t.join();
  meshes_done = true;
  single.join();
  MESSAGE("maximum meshes: " << ok.load() << " answered, " << refused.load() << " refused; single points "
                             << singles_ok.load() << " of " << singles.load() << " answered");
  CHECK(ok.load() >= 1);
  CHECK(refused.load() >= 1);  // not all eight were admitted at once
  CHECK(ok.load() + refused.load() == 8);
  CHECK(singles.load() >= 1);
  CHECK(singles_ok.load() == singles.load());
  for (const auto& r : refusals) {
    CHECK(r.rfind("503 1 ", 0) == 0);
    CHECK(r.find("\"code\":\"overloaded\"") != std::string::npos);
    CHECK(r.find("--max-inflight-bytes") != std::string::npos);
  }
  auto m = c->Get("/metrics");
  REQUIRE(m);
  CHECK(m->body.find("\nfootpoint_memory_refusals_total " + std::to_string(refused.load()) + "\n") !=
        std::string::npos);
  CHECK(m->body.find("\nfootpoint_memory_budget_bytes 157286400\n") != std::string::npos);
  CHECK(m->body.find("\nfootpoint_memory_in_flight_bytes 0\n") != std::string::npos);
}

// A loopback port that was free a moment ago.
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  socklen_t length = sizeof addr;
  REQUIRE(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length) == 0);
  ::close(fd);
  return ntohs(addr.sin_port);
}

TEST_CASE("isolation: --probe-port answers while slow clients hold every connection thread") {
  ServerConfig config;
  config.connection_threads = 4;
  config.io_timeout_s = 4;
  config.probe_port = free_port();
  TestServer s(config);
  // Four clients that send half a request line and then nothing: each holds a connection thread
  // until the read timeout.
  std::vector<int> slow;
  for (int i = 0; i < 4; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    REQUIRE(fd >= 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(s.port()));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
    REQUIRE(::send(fd, "GET /healthz HT", 15, MSG_NOSIGNAL) == 15);
    slow.push_back(fd);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto api = s.client();
  api->set_read_timeout(1, 0);
  CHECK_FALSE(api->Get("/healthz"));  // queued behind the slow clients
  httplib::Client probe_client("127.0.0.1", config.probe_port);
  probe_client.set_read_timeout(1, 0);
  for (const char* path : {"/healthz", "/readyz"}) {
    auto r = probe_client.Get(path);
    REQUIRE(r);
    CHECK(r->status == 200);
    CHECK(json::parse(r->body).contains("status"));
  }
  auto r = probe_client.Get("/v1/methods");
  REQUIRE(r);
  CHECK(r->status == 404);  // the probe port serves the probes only
  for (const int fd : slow) ::close(fd);
}

TEST_CASE("TLS: HTTPS only, TLS 1.2 and later, the certificate reread while a request is in flight") {
  TempDir dir;
  make_certificate(dir, "first");
  make_certificate(dir, "second");
  std::filesystem::copy_file(dir.file("first.crt"), dir.file("served.crt"));
  std::filesystem::copy_file(dir.file("first.key"), dir.file("served.key"));
  ServerConfig config;
  config.tls_cert = dir.file("served.crt");
  config.tls_key = dir.file("served.key");
  HttpServer* self = nullptr;
  // /v1/methods answers after 800 ms: a request in flight while the certificate changes.
  TestServer s(config, [&self](const RouteMatch& m, std::string_view method, std::string_view body,
                               std::string_view query, const Caller& caller) {
    if (m.route == Route::methods) std::this_thread::sleep_for(std::chrono::milliseconds(800));
    return self->api().handle(m, method, body, query, caller);
  });
  self = &s.server();
  CHECK(s.server().tls());

  auto r = s.tls_client(dir.file("first.crt"))->Get("/healthz");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK_FALSE(s.tls_client(dir.file("second.crt"))->Get("/healthz"));  // not the certificate served

  // Plain HTTP to the TLS port gets no HTTP response.
  const std::string plain = raw_exchange(s.port(), "GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
                                         std::chrono::milliseconds(3000));
  CHECK(raw_status(plain) == -1);
  CHECK(plain.find("\"status\"") == std::string::npos);

  // A client that offers TLS 1.1 at most (its own security level lowered so that it may) is
  // refused; the same client allowed TLS 1.2 is served.
  for (const int max_version : {TLS1_1_VERSION, TLS1_2_VERSION}) {
    auto old_client = s.tls_client(dir.file("first.crt"));
    SSL_CTX* ctx = old_client->ssl_context();
    REQUIRE(ctx != nullptr);
    SSL_CTX_set_security_level(ctx, 0);
    REQUIRE(SSL_CTX_set_min_proto_version(ctx, TLS1_VERSION) == 1);
    REQUIRE(SSL_CTX_set_max_proto_version(ctx, max_version) == 1);
    REQUIRE(SSL_CTX_set_cipher_list(ctx, "ALL:@SECLEVEL=0") == 1);
    auto answer = old_client->Get("/healthz");
    CAPTURE(max_version);
    CHECK(static_cast<bool>(answer) == (max_version == TLS1_2_VERSION));
  }

  int slow_status = 0;
  std::string slow_body;
  std::thread in_flight([&] {
    if (auto answer = s.tls_client(dir.file("first.crt"))->Get("/v1/methods")) {
      slow_status = answer->status;
      slow_body = answer->body;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  std::filesystem::copy_file(dir.file("second.crt"), dir.file("served.crt"),
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir.file("second.key"), dir.file("served.key"),
                             std::filesystem::copy_options::overwrite_existing);
  CHECK(s.server().reload());
  r = s.tls_client(dir.file("second.crt"))->Get("/healthz");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK_FALSE(s.tls_client(dir.file("first.crt"))->Get("/healthz"));
  in_flight.join();
  REQUIRE(slow_status == 200);
  CHECK(json::parse(slow_body).contains("geometry_types"));

  // A key that is not the certificate's: refused, the served certificate stays.
  std::filesystem::copy_file(dir.file("first.key"), dir.file("served.key"),
                             std::filesystem::copy_options::overwrite_existing);
  CHECK_FALSE(s.server().reload());
  r = s.tls_client(dir.file("second.crt"))->Get("/healthz");
  REQUIRE(r);
  CHECK(r->status == 200);
  // Starting with a broken pair fails.
  config.tls_key = dir.file("first.key");
  config.tls_cert = dir.file("second.crt");
  CHECK_THROWS_WITH(HttpServer{test_config(config)}, doctest::Contains("is not the private key"));
}

}  // namespace access_test
}  // namespace
