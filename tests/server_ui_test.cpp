// The browser pages as the server serves them: / and /docs are the embedded ui/index.html and
// ui/docs.html, every /ui/{file} is the file byte for byte (three.js as Debian's libjs-three ships
// it), each with Content-Security-Policy default-src 'self'; the pages run no inline script and
// load nothing from elsewhere; --ui off answers them 404 and leaves the API alone.
#include <doctest/doctest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "server_support.hpp"
#include "ui_files.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;

namespace {

std::string source_of(const std::string& name) {
  if (name == "three.min.js") return read_text_file(FOOTPOINT_THREE_DIR "/three.min.js");
  if (name == "OrbitControls.js")
    return read_text_file(FOOTPOINT_THREE_DIR "/examples/js/controls/OrbitControls.js");
  return read_text_file(FOOTPOINT_SOURCE_DIR "/ui/" + name);
}

}  // namespace

TEST_CASE("the pages and their files, byte for byte, with their security policy") {
  TestServer s;
  auto c = s.client();
  const struct {
    const char* path;
    const char* file;
  } pages[] = {{"/", "index.html"}, {"/docs", "docs.html"}};
  for (const auto& p : pages) {
    auto r = c->Get(p.path);
    REQUIRE(r);
    CHECK(r->status == 200);
    CHECK(r->get_header_value("Content-Type") == "text/html; charset=utf-8");
    CHECK(r->get_header_value("Content-Security-Policy") == "default-src 'self'");
    CHECK(r->body == source_of(p.file));
  }
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FOOTPOINT_SOURCE_DIR "/ui")) {
    const std::string name = entry.path().filename().string();
    ++files;
    auto r = c->Get(("/ui/" + name).c_str());
    REQUIRE(r);
    INFO(name);
    CHECK(r->status == 200);
    CHECK(r->get_header_value("Content-Security-Policy") == "default-src 'self'");
    CHECK(r->get_header_value("X-Content-Type-Options") == "nosniff");
    CHECK(r->body == source_of(name));
  }
  CHECK(ui_files().size() == files + 2);  // ui/ and three.js with its orbit controls
  for (const char* name : {"three.min.js", "OrbitControls.js"}) {
    auto r = c->Get((std::string("/ui/") + name).c_str());
    REQUIRE(r);
    CHECK(r->status == 200);
    CHECK(r->get_header_value("Content-Type") == "text/javascript; charset=utf-8");
    CHECK(r->body == source_of(name));
  }
  auto missing = c->Get("/ui/nope.js");
  REQUIRE(missing);
  CHECK(missing->status == 404);
  CHECK(nlohmann::json::parse(missing->body)["error"]["code"] == "route_not_found");
  auto post = c->Post("/", "{}", "application/json");
  REQUIRE(post);
  CHECK(post->status == 405);
}

TEST_CASE("the pages run no inline script and load nothing from another origin") {
  // Script only from files (<script src>), no event-handler attributes, no style attributes, and
  // no absolute URL but XML namespaces (the icon's xmlns).
  const std::regex inline_script(R"(<script(?![^>]*\bsrc=)[^>]*>)", std::regex::icase);
  const std::regex handler_attribute(R"(<[^>]*\son[a-z]+\s*=)", std::regex::icase);
  const std::regex style_attribute(R"(<[^>]*\sstyle\s*=)", std::regex::icase);
  const std::regex absolute_url(R"(https?://(?!www\.w3\.org/)[^\s"'<>)]*)", std::regex::icase);
  for (const auto& file : ui_files()) {
    if (file.name == "three.min.js" || file.name == "OrbitControls.js") continue;
    const std::string text(file.text);
    INFO(file.name);
    CHECK_FALSE(std::regex_search(text, inline_script));
    CHECK_FALSE(std::regex_search(text, handler_attribute));
    CHECK_FALSE(std::regex_search(text, style_attribute));
    std::smatch m;
    CHECK_MESSAGE(!std::regex_search(text, m, absolute_url), m.str());
  }
}

TEST_CASE("--ui off: the pages answer 404, the API stays") {
  ServerConfig config;
  config.ui = false;
  TestServer s(config);
  auto c = s.client();
  for (const char* path : {"/", "/docs", "/ui/playground.js", "/ui/three.min.js"}) {
    auto r = c->Get(path);
    REQUIRE(r);
    INFO(path);
    CHECK(r->status == 404);
    CHECK(nlohmann::json::parse(r->body)["error"]["code"] == "route_not_found");
  }
  auto methods = c->Get("/v1/methods");
  REQUIRE(methods);
  CHECK(methods->status == 200);
  auto openapi = c->Get("/openapi.yaml");
  REQUIRE(openapi);
  CHECK(openapi->status == 200);
}
