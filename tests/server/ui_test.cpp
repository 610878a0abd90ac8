// The browser pages as the server serves them: / and /docs are the embedded ui/index.html and
// ui/docs.html, every /ui/{file} is the file byte for byte (three.js as Debian's libjs-three ships
// it, Swagger UI's bundle as npm's swagger-ui-dist ships it), each with Content-Security-Policy
// default-src 'self'; Swagger UI's style sheet is npm's with its data: images (which that policy
// refuses) served as files; the pages run no inline script and load nothing from elsewhere; --ui
// off answers them 404 and leaves the API alone.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "server_support.hpp"
#include "ui_files.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;

namespace {

std::string source_of(const std::string& name) {
  if (name == "three.min.js") return read_text_file(FOOTPOINT_THREE_DIR "/three.min.js");
  if (name == "swagger-ui-bundle.js") return read_text_file(FOOTPOINT_SWAGGER_UI_DIR "/swagger-ui-bundle.js");
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
    if (!entry.is_regular_file()) continue;  // ui/vendor/ pins Swagger UI
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
  std::size_t swagger_images = 0;
  for (const auto& file : ui_files()) swagger_images += file.name.starts_with("swagger-ui-image-");
  // ui/, three.js with its orbit controls, Swagger UI's bundle, style sheet and images.
  CHECK(ui_files().size() == files + 4 + swagger_images);
  for (const char* name : {"three.min.js", "OrbitControls.js", "swagger-ui-bundle.js"}) {
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

namespace {

// Swagger UI's style sheet as npm ships it: its SVG images as data: URLs in CSS strings (RFC 2397;
// CSS Syntax Level 3 §4.3.7 escapes, RFC 3986 §2.1 percent-encoding), base64 rasters for the
// unused .debug-grid classes. What the server must serve instead: the same text with each SVG as
// url("/ui/swagger-ui-image-N.svg") (N counting distinct images in order of first use), each
// raster as none; and the images themselves.
struct SwaggerStyles {
  std::string css;
  std::vector<std::string> images;
};

SwaggerStyles swagger_styles_without_data_urls(const std::string& css) {
  const std::string svg = "url(\"data:image/svg+xml;charset=utf-8,";
  const std::string raster = "url(data:image/";
  SwaggerStyles out;
  std::size_t at = 0;
  for (;;) {
    const std::size_t next = css.find("url(", at);
    out.css += css.substr(at, next == std::string::npos ? std::string::npos : next - at);
    if (next == std::string::npos) break;
    if (css.compare(next, svg.size(), svg) == 0) {
      std::string image;
      std::size_t i = next + svg.size();
      for (; css.at(i) != '"'; ++i) {
        if (css[i] == '\\') {
          ++i;  // an escaped character: the images escape only quotes
          REQUIRE_FALSE(std::isxdigit(static_cast<unsigned char>(css[i])));
          image += css[i];
        } else if (css[i] == '%') {
          image += static_cast<char>(std::stoi(css.substr(i + 1, 2), nullptr, 16));
          i += 2;
        } else {
          image += css[i];
        }
      }
      REQUIRE(css.at(i + 1) == ')');
      const auto known = std::find(out.images.begin(), out.images.end(), image);
      const std::size_t n = static_cast<std::size_t>(known - out.images.begin()) + 1;
      if (known == out.images.end()) out.images.push_back(image);
      out.css += "url(\"/ui/swagger-ui-image-" + std::to_string(n) + ".svg\")";
      at = i + 2;
    } else if (css.compare(next, raster.size(), raster) == 0) {
      out.css += "none";
      const std::size_t end = css.find(')', next);
      REQUIRE(end != std::string::npos);
      at = end + 1;
    } else {
      out.css += "url(";
      at = next + 4;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("Swagger UI's style sheet: npm's, its data: images served as files of this origin") {
  const std::string original = read_text_file(FOOTPOINT_SWAGGER_UI_DIR "/swagger-ui.css");
  REQUIRE(original.find("data:image/svg+xml") != std::string::npos);
  const SwaggerStyles want = swagger_styles_without_data_urls(original);
  TestServer s;
  auto c = s.client();
  auto css = c->Get("/ui/swagger-ui.css");
  REQUIRE(css);
  CHECK(css->status == 200);
  CHECK(css->get_header_value("Content-Type") == "text/css; charset=utf-8");
  CHECK(css->body == want.css);
  CHECK(css->body.find("data:") == std::string::npos);
  REQUIRE_FALSE(want.images.empty());
  for (std::size_t n = 1; n <= want.images.size(); ++n) {
    const std::string path = "/ui/swagger-ui-image-" + std::to_string(n) + ".svg";
    INFO(path);
    auto r = c->Get(path.c_str());
    REQUIRE(r);
    CHECK(r->status == 200);
    CHECK(r->get_header_value("Content-Type") == "image/svg+xml");
    CHECK(r->get_header_value("Content-Security-Policy") == "default-src 'self'");
    CHECK(r->body == want.images[n - 1]);
    CHECK(r->body.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
  }
  auto beyond = c->Get(("/ui/swagger-ui-image-" + std::to_string(want.images.size() + 1) + ".svg").c_str());
  REQUIRE(beyond);
  CHECK(beyond->status == 404);
}

TEST_CASE("the pages run no inline script and load nothing from another origin") {
  // Script only from files (<script src>), no event-handler attributes, no style attributes, and
  // no absolute URL but XML namespaces (the icon's xmlns).
  const std::regex inline_script(R"(<script(?![^>]*\bsrc=)[^>]*>)", std::regex::icase);
  const std::regex handler_attribute(R"(<[^>]*\son[a-z]+\s*=)", std::regex::icase);
  const std::regex style_attribute(R"(<[^>]*\sstyle\s*=)", std::regex::icase);
  const std::regex absolute_url(R"(https?://(?!www\.w3\.org/)[^\s"'<>)]*)", std::regex::icase);
  for (const auto& file : ui_files()) {
    // Third-party files: three.js; Swagger UI, whose bundle names the specifications it reads.
    if (file.name == "three.min.js" || file.name == "OrbitControls.js" || file.name.starts_with("swagger-ui"))
      continue;
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
