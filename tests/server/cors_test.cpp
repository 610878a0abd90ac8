// CORS for configured origins: off by default; on, a preflight OPTIONS is answered with the
// route's methods, and the configured origins' requests (errors too) may be read by their pages.
#include <doctest/doctest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const std::string kCurve = R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,6]}})J";
const std::string kApp = "https://app.example.com";

httplib::Result preflight(httplib::Client& c, const std::string& path, const std::string& origin) {
  return c.Options(path, {{"Origin", origin},
                          {"Access-Control-Request-Method", "POST"},
                          {"Access-Control-Request-Headers", "content-type"}});
}

}  // namespace

TEST_CASE("CORS is off by default: OPTIONS is not allowed, no Access-Control header is sent") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kCurve);
  auto r = preflight(*c, "/v1/geometries/" + id + "/project", kApp);
  REQUIRE(r);
  CHECK(r->status == 405);
  CHECK(json::parse(r->body)["error"]["code"] == "method_not_allowed");
  r = c->Post("/v1/geometries/" + id + "/project", {{"Origin", kApp}}, R"J({"point":[2,0]})J",
              "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK_FALSE(r->has_header("Access-Control-Allow-Origin"));
}

TEST_CASE("CORS for configured origins: preflight, responses and errors readable, other origins refused") {
  ServerConfig config;
  config.cors_origins = {kApp, "http://localhost:3000"};
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kCurve);
  const std::string project = "/v1/geometries/" + id + "/project";

  auto r = preflight(*c, project, kApp);
  REQUIRE(r);
  CHECK(r->status == 204);
  CHECK(r->body.empty());
  CHECK(r->get_header_value("Access-Control-Allow-Origin") == kApp);
  CHECK(r->get_header_value("Access-Control-Allow-Methods") == "POST");
  CHECK(r->get_header_value("Access-Control-Allow-Headers") == "Authorization, Content-Type, X-Request-Id");
  CHECK(r->get_header_value("Access-Control-Max-Age") == "600");
  CHECK(r->get_header_value("Vary") == "Origin");
  r = preflight(*c, "/v1/geometries", "http://localhost:3000");
  REQUIRE(r);
  CHECK(r->status == 204);
  CHECK(r->get_header_value("Access-Control-Allow-Methods") == "GET, HEAD, POST");

  r = c->Post(project, {{"Origin", kApp}}, R"J({"point":[2,0]})J", "application/json");
  REQUIRE(r);
  CHECK(r->status == 200);
  CHECK(r->get_header_value("Access-Control-Allow-Origin") == kApp);
  CHECK(r->get_header_value("Access-Control-Expose-Headers").find("X-Request-Id") != std::string::npos);
  r = c->Post(project, {{"Origin", kApp}}, R"J({"point":[2,0,1]})J", "application/json");
  REQUIRE(r);
  CHECK(r->status == 400);  // the page can read why
  CHECK(r->get_header_value("Access-Control-Allow-Origin") == kApp);

  r = preflight(*c, project, "https://evil.example.com");
  REQUIRE(r);
  CHECK(r->status == 403);
  CHECK(json::parse(r->body)["error"]["code"] == "origin_not_allowed");
  CHECK_FALSE(r->has_header("Access-Control-Allow-Origin"));
  r = c->Post(project, {{"Origin", "https://evil.example.com"}}, R"J({"point":[2,0]})J", "application/json");
  REQUIRE(r);
  CHECK_FALSE(r->has_header("Access-Control-Allow-Origin"));  // the browser keeps it from the page
  // Same-origin and non-browser requests carry no Origin: nothing changes for them.
  r = c->Get("/healthz");
  REQUIRE(r);
  CHECK_FALSE(r->has_header("Access-Control-Allow-Origin"));
}

TEST_CASE("CORS for any origin, and the flag's checks") {
  ServerConfig config;
  config.cors_origins = {"*"};
  TestServer s(config);
  auto c = s.client();
  auto r = preflight(*c, "/v1/project", "https://anywhere.example.org");
  REQUIRE(r);
  CHECK(r->status == 204);
  CHECK(r->get_header_value("Access-Control-Allow-Origin") == "*");

  auto parse = [](const char* value) {
    const char* argv[] = {"footpoint-server", "--cors-origins", value};
    bool help = false;
    return load_config(3, argv, nullptr, help);
  };
  CHECK(parse("https://a.example.com, http://localhost:3000").cors_origins ==
        std::vector<std::string>{"https://a.example.com", "http://localhost:3000"});
  CHECK(parse("").cors_origins.empty());
  CHECK_THROWS_AS(parse("ftp://a.example.com"), ConfigError);
  CHECK_THROWS_AS(parse("https://a.example.com/app"), ConfigError);
  CHECK_THROWS_AS(parse("a.example.com"), ConfigError);
  CHECK_THROWS_AS(parse("https://"), ConfigError);
}
