// The JSON layer of the server: the pull reader, the writer, and the request/definition parsers
// (shapes, field names, positions), without HTTP.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "api_error.hpp"
#include "config.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "json_writer.hpp"
#include "project_request.hpp"

using namespace footpoint;
using namespace footpoint::server;

namespace {

// The ApiError a call throws (fails the test when it throws nothing).
template <class F>
ApiError api_error_of(F&& f) {
  try {
    f();
  } catch (const ApiError& e) {
    return e;
  }
  FAIL("no ApiError thrown");
  return ApiError(0, "", "");
}

JsonReadError read_error_of(std::string_view text) {
  try {
    JsonReader r(text);
    r.skip();
    r.finish();
  } catch (const JsonReadError& e) {
    return e;
  }
  FAIL("no JsonReadError for " << text);
  return JsonReadError(JsonReadError::Kind::syntax, 0, "");
}

}  // namespace

TEST_CASE("numbers written by JsonWriter read back bit-identical") {
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<std::uint64_t> bits;
  std::string text = "[";
  std::vector<double> values;
  JsonWriter w;
  w.begin_array();
  for (int i = 0; i < 20000; ++i) {
    double x = std::bit_cast<double>(bits(rng));  // every exponent, subnormals included
    if (!std::isfinite(x)) continue;
    values.push_back(x);
    w.number(x);
  }
  for (double x : {0.0, -0.0, 0.1, 1e300, 5e-324, std::numeric_limits<double>::max(), 123456789.0}) {
    values.push_back(x);
    w.number(x);
  }
  w.end_array();
  JsonReader r(w.str());
  r.begin_array();
  std::size_t i = 0;
  while (r.next_element()) {
    const double y = r.number();
    REQUIRE(i < values.size());
    CHECK(std::bit_cast<std::uint64_t>(y) == std::bit_cast<std::uint64_t>(values[i]));
    ++i;
  }
  r.finish();
  CHECK(i == values.size());
  // The shortest form: what nlohmann (strtod) reads is the same double too.
  const auto j = nlohmann::json::parse(w.str());
  for (std::size_t k = 0; k < values.size(); ++k) CHECK(j[k].get<double>() == values[k]);
}

TEST_CASE("non-finite numbers are written as null") {
  JsonWriter w;
  w.begin_array();
  w.number(std::nan(""));
  w.number(std::numeric_limits<double>::infinity());
  w.number(1.5);
  w.end_array();
  CHECK(w.str() == "[null,null,1.5]");
}

TEST_CASE("strings: escapes and UTF-8 survive a round trip") {
  const std::string s = "quote\" backslash\\ newline\n tab\t ctrl\x01 \xC3\xA9 \xF0\x9F\x98\x80 /";
  JsonWriter w;
  w.string(s);
  CHECK(nlohmann::json::parse(w.str()).get<std::string>() == s);
  JsonReader r(w.str());
  CHECK(r.string() == s);
  JsonReader u(R"J("\u00e9\ud83d\ude00\/")J");
  CHECK(u.string() == "\xC3\xA9\xF0\x9F\x98\x80/");
}

TEST_CASE("strings: bytes that are no UTF-8 are written as U+FFFD, valid text as it is") {
  // well-formed: 2-, 3- and 4-byte sequences at the edges of their ranges (U+0080, U+07FF, U+0800,
  // U+D7FF, U+E000, U+FFFF, U+10000, U+10FFFF)
  const std::string valid =
      "\xC2\x80\xDF\xBF\xE0\xA0\x80\xED\x9F\xBF\xEE\x80\x80\xEF\xBF\xBF\xF0\x90\x80\x80\xF4\x8F\xBF\xBF";
  std::string out;
  append_json_string(out, valid);
  CHECK(out == '"' + valid + '"');
  const struct {
    std::string in, expected;  // expected: the string the JSON text holds, \uFFFD as UTF-8
  } cases[] = {
      {"a\x80z", "a\xEF\xBF\xBDz"},                                              // a lone continuation byte
      {"\xC0\xAF", "\xEF\xBF\xBD\xEF\xBF\xBD"},                                  // an overlong '/'
      {"\xE0\x80\xAF", "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD"},                  // an overlong 3-byte form
      {"\xED\xA0\x80", "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD"},                  // a surrogate, U+D800
      {"\xF4\x90\x80\x80", "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD"},  // past U+10FFFF
      {"x\xE2\x82", "x\xEF\xBF\xBD\xEF\xBF\xBD"},                                // cut short at the end
      {"\xF5\xFF\\", "\xEF\xBF\xBD\xEF\xBF\xBD\\"},  // never in UTF-8; an escape after
  };
  for (const auto& c : cases) {
    out.clear();
    append_json_string(out, c.in);
    INFO(out);
    CHECK(nlohmann::json::parse(out).get<std::string>() == c.expected);
  }
}

TEST_CASE("the reader rejects what is not JSON, with the byte position") {
  struct Bad {
    const char* text;
    std::size_t position;
  };
  const Bad cases[] = {
      {"[1,]", 3},  {"[1 2]", 3},       {"{\"a\":1,}", 7},         {"[01]", 2},          {"[1.]", 3},
      {"[-]", 2},   {"[NaN]", 1},       {"[Infinity]", 1},         {"[+1]", 1},          {"[1e]", 3},
      {"\"abc", 4}, {"[\"a\x01\"]", 3}, {"[\"\\x\"]", 2},          {"[tru]", 1},         {"{\"a\" 1}", 5},
      {"[1] x", 4}, {"[\"\xC3\"]", 2},  {"[\"\xED\xA0\x80\"]", 2}, {"[\"\\ud800\"]", 8}, {"", 0},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const auto e = read_error_of(c.text);
    CHECK(e.kind == JsonReadError::Kind::syntax);
    CHECK(e.position == c.position);
  }
  JsonReader big("[1e400]");
  big.begin_array();
  big.next_element();
  try {
    big.number();
    FAIL("1e400 read as a double");
  } catch (const JsonReadError& e) {
    CHECK(e.kind == JsonReadError::Kind::range);
    CHECK(e.position == 1);
  }
  JsonReader tiny("1e-400");
  CHECK(tiny.number() == 0.0);
}

TEST_CASE("nesting deeper than the limit is refused, not recursed into") {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const auto e = read_error_of(deep);
  CHECK(e.kind == JsonReadError::Kind::syntax);
  CHECK(e.position == 64);
}

TEST_CASE("project requests: points, options and their errors name the field") {
  const auto ok = read_project_request(
      R"J({"points":[[1,2,3],[4,5,6.5]],"method":"gsa","options":{"tolerance":1e-12,"max_iterations":50,
          "initial":[[0,1],[2,3]],"all_minima":true,"trace":false,"max_distance":10}})J",
      false, 100);
  CHECK_FALSE(ok.single);
  CHECK(ok.count == 2);
  CHECK(ok.point_length == 3);
  CHECK(ok.coords == std::vector<double>{1, 2, 3, 4, 5, 6.5});
  CHECK(ok.method == "gsa");
  CHECK(ok.options.tolerance == 1e-12);
  CHECK(ok.options.max_iterations == 50);
  CHECK(ok.options.all_minima);
  CHECK(ok.options.max_distance == 10);
  CHECK(ok.initials.size() == 2);
  CHECK(ok.initial_length == 2);

  const auto one = read_project_request(R"J({"point":[1,2],"options":{"initial":[0.5]}})J", false, 100);
  CHECK(one.single);
  CHECK(one.point_length == 2);
  CHECK(one.options.initial.has_value());
  CHECK(one.initial_length == 1);

  struct Bad {
    const char* body;
    int status;
    const char* code;
    const char* field;
  };
  const Bad cases[] = {
      {R"J({"points":[[1,2,3],[1,"a",3]]})J", 400, "wrong_type", "points[1][1]"},
      {R"J({"points":[[1,2,3],5]})J", 400, "wrong_type", "points[1]"},
      {R"J({"points":{"a":1}})J", 400, "wrong_type", "points"},
      {R"J({"points":[[1,2,3],[1,2]]})J", 400, "wrong_dimension", "points[1]"},
      {R"J({"points":[[1,2,3,4]]})J", 400, "wrong_dimension", "points[0]"},
      {R"J({"points":[[]]})J", 400, "wrong_dimension", "points[0]"},
      {R"J({"points":[]})J", 400, "empty_batch", "points"},
      {R"J({"points":[[1,2,1e400]]})J", 400, "number_out_of_range", "points[0][2]"},
      {R"J({"points":[[1,2,NaN]]})J", 400, "malformed_json", ""},
      {R"J({"point":[1,2,3],"points":[[1,2,3]]})J", 400, "conflicting_fields", "points"},
      {R"J({"method":"auto"})J", 400, "missing_field", "point"},
      {R"J({"point":[1,2,3],"pont":1})J", 400, "unknown_field", "pont"},
      {R"J({"point":[1,2,3],"point":[1,2,3]})J", 400, "duplicate_field", "point"},
      {R"J({"point":[1,2,3],"options":{"tolerance":-1}})J", 400, "invalid_option", "options.tolerance"},
      {R"J({"point":[1,2,3],"options":{"max_iterations":1e9}})J", 400, "invalid_option",
       "options.max_iterations"},
      {R"J({"point":[1,2,3],"options":{"max_iterations":2.5}})J", 400, "invalid_option",
       "options.max_iterations"},
      {R"J({"point":[1,2,3],"options":{"trace":1}})J", 400, "wrong_type", "options.trace"},
      {R"J({"point":[1,2,3],"options":{"speed":1}})J", 400, "unknown_field", "options.speed"},
      {R"J({"points":[[1,2,3]],"options":{"initial":[[1,2],[3,4]]}})J", 400, "wrong_shape",
       "options.initial"},
      {R"J({"point":[1,2,3],"geometry":{}})J", 400, "unknown_field", "geometry"},
      {R"J({"point":[1,2,3]} extra)J", 400, "malformed_json", ""},
      {R"J([1,2,3])J", 400, "wrong_type", "body"},
      {R"J({"points":[[1,2,3],[1,2,3],[1,2,3]]})J", 413, "too_many_points", "points"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.body);
    const auto e = api_error_of([&] { read_project_request(c.body, false, 2); });
    CHECK(e.status == c.status);
    CHECK(e.code == c.code);
    CHECK(e.field == c.field);
  }
  const auto syntax = api_error_of([] { read_project_request(R"J({"point":[1,2,]})J", false, 2); });
  CHECK(syntax.position == 14);
}

TEST_CASE("geometry definitions: canonical order, and shape errors name the field") {
  JsonReader r(R"J({"domain":{"v":[0,2],"u":[-1,1]},"z":"u*v","y":"v","x":"u","type":"parametric_surface",
                  "constants":{"R":2}})J");
  const GeometryDefinition def = read_geometry(r, "");
  r.finish();
  CHECK(def.type == GeometryType::parametric_surface);
  REQUIRE(def.formulas.size() == 3);
  CHECK(def.formulas[0].name == "x");
  CHECK(def.formulas[2].expression == "u*v");
  REQUIRE(def.domain.size() == 2);
  CHECK(def.domain[0].first == "u");
  CHECK(def.domain[1].second[1] == 2.0);
  CHECK(def.constants.at("R") == 2.0);
  // Written back, it reads as the same definition (same id).
  JsonWriter w;
  write_geometry(w, def);
  JsonReader again(w.str());
  CHECK(read_geometry(again, "").id() == def.id());

  struct Bad {
    const char* body;
    const char* code;
    const char* field;
  };
  const Bad cases[] = {
      {R"J({"x":"u","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1]}})J", "missing_field", "geometry.type"},
      {R"J({"type":"sphere"})J", "unknown_geometry_type", "geometry.type"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","domain":{"u":[0,1],"v":[0,1]}})J", "missing_field",
       "geometry.z"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":1,"domain":{"u":[0,1],"v":[0,1]}})J",
       "wrong_type", "geometry.z"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1]}})J", "missing_field",
       "geometry.domain.v"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1],"t":[0,1]}})J",
       "unknown_field", "geometry.domain.t"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1,2],"v":[0,1]}})J",
       "wrong_shape", "geometry.domain.u"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,true],"v":[0,1]}})J",
       "wrong_type", "geometry.domain.u[1]"},
      {R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":{"lo":0,"hi":1},"v":[0,1]}})J",
       "wrong_type", "geometry.domain.u"},
      {R"J({"type":"parametric_curve","x":"t","y":"t","equations":["x"],"domain":{"t":[0,1]}})J",
       "unknown_field", "geometry.equations"},
      {R"J({"type":"implicit_curve","equations":[],"domain":{"x":[0,1],"y":[0,1]}})J", "wrong_shape",
       "geometry.equations"},
      {R"J({"type":"implicit_curve","equations":["x","y","z"],"domain":{"x":[0,1],"y":[0,1]}})J",
       "wrong_shape", "geometry.equations"},
      {R"J({"type":"implicit_curve","equations":["x^2+y^2-1"],"domain":{"x":[0,1],"y":[0,1],"z":[0,1]}})J",
       "unknown_field", "geometry.domain.z"},
      {R"J({"type":"implicit_curve","x":"t","equations":["x"],"domain":{"x":[0,1],"y":[0,1]}})J",
       "unknown_field", "geometry.x"},
      {R"J({"type":"implicit_surface","domain":{"x":[0,1],"y":[0,1],"z":[0,1]}})J", "missing_field",
       "geometry.equation"},
      {R"J({"type":"implicit_surface","equations":["x"],"domain":{"x":[0,1],"y":[0,1],"z":[0,1]}})J",
       "unknown_field", "geometry.equations"},
      {R"J({"type":"implicit_surface","equation":"x+y+z","domain":{"x":[0,1],"y":[0,1]}})J", "missing_field",
       "geometry.domain.z"},
      {R"J({"type":"implicit_curve","equation":"x","equations":["x"],"domain":{"x":[0,1],"y":[0,1]}})J",
       "unknown_field", "geometry.equation"},
      {R"J({"type":"implicit_surface","equation":["x"],"domain":{"x":[0,1],"y":[0,1],"z":[0,1]}})J",
       "wrong_type", "geometry.equation"},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,1]},"constants":{"R":"2"}})J",
       "wrong_type", "geometry.constants.R"},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,1]},"color":"red"})J", "unknown_field",
       "geometry.color"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.body);
    const auto e = api_error_of([&] {
      JsonReader reader(c.body);
      read_geometry(reader, "geometry.");
    });
    CHECK(e.status == 400);
    CHECK(e.code == c.code);
    CHECK(e.field == c.field);
  }
}

TEST_CASE("domain bounds as constant expressions: evaluated before the id, errors as for formulas") {
  auto read = [](const std::string& body) {
    JsonReader reader(body);
    return read_geometry(reader, "geometry.");
  };
  const GeometryDefinition by_expression = read(
      R"J({"type":"parametric_curve","x":"R*cos(t)","y":"R*sin(t)","domain":{"t":["-_pi/2", "2*_pi+R-R"]},
           "constants":{"R":1.5}})J");
  const GeometryDefinition by_number = read(
      R"J({"type":"parametric_curve","x":"R*cos(t)","y":"R*sin(t)","domain":{"t":[-1.5707963267948966, 6.283185307179586]},
           "constants":{"R":1.5}})J");
  CHECK(by_expression.domain[0].second[0] == -1.5707963267948966);
  CHECK(by_expression.domain[0].second[1] == 6.283185307179586);
  CHECK(by_expression.id() == by_number.id());
  CHECK(by_expression.canonical().find("domain.t=[-1.5707963267948966,6.283185307179586]") !=
        std::string::npos);

  struct Bad {
    const char* body;
    const char* code;
    const char* field;
    int position;
    const char* suggestion;
  };
  const Bad cases[] = {
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,"2*pi"]}})J", "unknown_variable",
       "geometry.domain.t[1]", 2, "_pi"},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":["t",1]}})J", "unknown_variable",
       "geometry.domain.t[0]", 0, ""},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,"2**3"]}})J", "formula_syntax",
       "geometry.domain.t[1]", 1, "^"},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,"sqrt(2"]}})J", "formula_syntax",
       "geometry.domain.t[1]", 4, ""},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0,"1/0"]}})J", "bad_domain",
       "geometry.domain.t[1]", -1, ""},
      {R"J({"type":"parametric_curve","x":"t","y":"t","domain":{"t":[0," "]}})J", "empty_formula",
       "geometry.domain.t[1]", -1, ""},
  };
  for (const auto& c : cases) {
    CAPTURE(c.body);
    const auto e = api_error_of([&] { read(c.body); });
    CHECK(e.status == 422);
    CHECK(e.code == c.code);
    CHECK(e.field == c.field);
    CHECK(e.position == c.position);
    CHECK(e.suggestion == c.suggestion);
  }
}

TEST_CASE("configuration: flags win over environment variables, which win over defaults") {
  const char* argv[] = {"footpoint-server", "--port", "9000", "--threads=3", "--cache-entries", "7"};
  auto env = [](const char* name) -> const char* {
    if (std::strcmp(name, "FOOTPOINT_PORT") == 0) return "8500";
    if (std::strcmp(name, "FOOTPOINT_HOST") == 0) return "127.0.0.1";
    if (std::strcmp(name, "FOOTPOINT_DEADLINE_MS") == 0) return "250";
    return nullptr;
  };
  bool help = false;
  const ServerConfig c = load_config(6, argv, env, help);
  CHECK_FALSE(help);
  CHECK(c.port == 9000);
  CHECK(c.host == "127.0.0.1");
  CHECK(c.threads == 3);
  CHECK(c.cache_entries == 7);
  CHECK(c.deadline.count() == 250);
  CHECK(c.max_points == ServerConfig{}.max_points);
  CHECK(c.effective_max_inflight() == 112);

  const char* bad_port[] = {"x", "--port", "70000"};
  CHECK_THROWS_AS(load_config(3, bad_port, nullptr, help), ConfigError);
  const char* unknown[] = {"x", "--prot", "1"};
  CHECK_THROWS_AS(load_config(3, unknown, nullptr, help), ConfigError);
  const char* missing[] = {"x", "--port"};
  CHECK_THROWS_AS(load_config(2, missing, nullptr, help), ConfigError);
  auto bad_env = [](const char* name) -> const char* {
    return std::strcmp(name, "FOOTPOINT_THREADS") == 0 ? "many" : nullptr;
  };
  const char* none[] = {"x"};
  CHECK_THROWS_AS(load_config(1, none, bad_env, help), ConfigError);
  const char* ask[] = {"x", "--help"};
  load_config(2, ask, nullptr, help);
  CHECK(help);
  CHECK(usage().find("FOOTPOINT_MAX_POINTS") != std::string::npos);
}
