// GET /v1/geometries: what this replica's cache holds, a page at a time in id order.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

json get_list(httplib::Client& c, const std::string& path, int status = 200) {
  auto r = c.Get(path);
  REQUIRE(r);
  INFO(r->body);
  REQUIRE(r->status == status);
  return json::parse(r->body);
}

}  // namespace

TEST_CASE("the list pages through every held geometry in id order, with its statistics") {
  TestServer s;
  auto c = s.client();
  CHECK(get_list(*c, "/v1/geometries") ==
        json{{"geometries", json::array()}, {"held", 0}, {"next", nullptr}});
  std::vector<std::string> ids;
  for (int k = 1; k <= 7; ++k)
    ids.push_back(create(*c, R"J({"type":"parametric_curve","x":"cos(t)","y":")J" + std::to_string(k) +
                                 R"J(*sin(t)","domain":{"t":[0,6]}})J"));
  std::sort(ids.begin(), ids.end());
  // Two lookups of the first id.
  c->Get("/v1/geometries/" + ids[0]);
  c->Get("/v1/geometries/" + ids[0]);

  std::vector<std::string> seen;
  std::string after;
  int pages = 0;
  for (;;) {
    const json page = get_list(*c, "/v1/geometries?limit=3" + (after.empty() ? "" : "&after=" + after));
    ++pages;
    CHECK(page["held"] == 7);
    CHECK(page["geometries"].size() <= 3);
    for (const auto& g : page["geometries"]) {
      seen.push_back(g["geometry_id"]);
      CHECK(g["type"] == "parametric_curve");
      CHECK(g["point_dim"] == 2);
      CHECK(g["num_params"] == 1);
      CHECK(g["memory_bytes"].get<long>() > 0);
    }
    if (page["next"].is_null()) break;
    after = page["next"];
    CHECK(after == seen.back());
  }
  CHECK(pages == 3);
  CHECK(seen == ids);
  const json first = get_list(*c, "/v1/geometries?limit=1");
  CHECK(first["geometries"][0]["hits"] == 2);
  // Listing is no use: it neither counts as a hit nor changes what the cache evicts first.
  CHECK(get_list(*c, "/v1/geometries?limit=1")["geometries"][0]["hits"] == 2);
  CHECK(get_list(*c, "/v1/geometries")["geometries"].size() == 7);  // the default limit, 100
}

TEST_CASE("the list's query: every bad parameter its 400") {
  TestServer s;
  auto c = s.client();
  struct Case {
    const char* query;
    const char* code;
    const char* field;
  };
  for (const Case& k :
       {Case{"limit=0", "number_out_of_range", "limit"}, Case{"limit=1001", "number_out_of_range", "limit"},
        Case{"limit=ten", "wrong_type", "limit"}, Case{"after=xyz", "invalid_geometry_id", "after"},
        Case{"limit=1&limit=2", "duplicate_field", "limit"}, Case{"page=2", "unknown_field", "page"}}) {
    CAPTURE(k.query);
    const json e = get_list(*c, std::string("/v1/geometries?") + k.query, 400);
    CHECK(e["error"]["code"] == k.code);
    CHECK(e["error"]["field"] == k.field);
  }
  auto r = c->Delete("/v1/geometries");
  REQUIRE(r);
  CHECK(r->status == 405);
  CHECK(r->get_header_value("Allow") == "GET, HEAD, POST");
}
