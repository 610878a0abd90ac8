// Every endpoint's responses, successes and errors, validated against openapi.yaml with a JSON
// Schema 2020-12 validator (Debian's python3-jsonschema and python3-yaml): the response schema is
// looked up by path, method, status and media type, so an undocumented status or a body that
// does not match its schema fails the test. Every operation of the document must be exercised.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "access.hpp"
#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

// Validates samples.json against openapi.yaml; prints one line per failure, exits 1 if any.
const char* const kValidator = R"PY(
import json, sys
import yaml
from jsonschema import Draft202012Validator

spec = yaml.safe_load(open(sys.argv[1]))
samples = json.load(open(sys.argv[2]))

def esc(s):
    return s.replace("~", "~0").replace("/", "~1")

def resolve(node, pointer):
    while "$ref" in node:
        pointer = node["$ref"]
        node = spec
        for part in pointer[2:].split("/"):
            node = node[part.replace("~1", "/").replace("~0", "~")]
    return node, pointer

failures = []
seen = set()
for s in samples:
    where = "%s %s -> %d" % (s["method"], s["template"], s["status"])
    item = spec["paths"].get(s["template"], {})
    method = s["method"].lower()
    if method not in item and s["status"] == 405:
        # A method the path does not have: its 405 is documented on the path's operations.
        method = next((m for m in item if m in ("get", "post", "delete")), method)
    else:
        seen.add((s["template"], method))
    op = item.get(method)
    if op is None:
        failures.append(where + ": operation not documented"); continue
    status = str(s["status"])
    if status not in op["responses"]:
        failures.append(where + ": status not documented"); continue
    pointer = "#/paths/%s/%s/responses/%s" % (esc(s["template"]), method, status)
    response, pointer = resolve(op["responses"][status], pointer)
    content = response.get("content")
    if not content:
        if s["body"]:
            failures.append(where + ": documented without a body, got one")
        continue
    media = s["content_type"].split(";")[0].strip()
    if media not in content:
        failures.append(where + ": media type %s not documented" % media); continue
    if s["method"] == "POST" and s["status"] < 300:
        # An accepted request must match the documented request body too.
        request_pointer = "#/paths/%s/post/requestBody/content/application~1json/schema" % esc(s["template"])
        root = dict(spec)
        root["$ref"] = request_pointer
        for e in list(Draft202012Validator(root).iter_errors(json.loads(s["request"])))[:3]:
            failures.append("%s: request body: %s at %s" % (where, e.message[:300], "/".join(map(str, e.path))))
    schema_pointer = pointer + "/content/" + esc(media) + "/schema"
    instance = json.loads(s["body"]) if media == "application/json" else s["body"]
    root = dict(spec)
    root["$ref"] = schema_pointer
    errors = sorted(Draft202012Validator(root).iter_errors(instance), key=lambda e: list(e.path))
    for e in errors[:3]:
        failures.append("%s: %s at %s" % (where, e.message[:300], "/".join(map(str, e.path))))
    # Without "fields" a result has every member x-required-without-fields lists.
    if (s["template"].endswith("/project") and media == "application/json" and s["status"] == 200
            and "fields" not in json.loads(s["request"])):
        result_schema = spec["components"]["schemas"]["ProjectionResult"]
        diagnostics_schema = spec["components"]["schemas"]["Diagnostics"]
        for r in ([instance["result"]] if "result" in instance else instance.get("results", [])):
            for name in result_schema["x-required-without-fields"]:
                if name not in r:
                    failures.append("%s: a result without fields lacks %s" % (where, name))
            for name in diagnostics_schema["x-required-without-fields"]:
                if name not in r.get("diagnostics", {}):
                    failures.append("%s: diagnostics without fields lack %s" % (where, name))

for path, ops in spec["paths"].items():
    for method in ops:
        if method in ("get", "post", "delete", "put", "patch") and (path, method) not in seen:
            failures.append("%s %s: no sample exercised it" % (method.upper(), path))

# Every operation shows what it answers: its success response has an example, and every example
# (responses and request bodies) matches its schema.
def check_example(where, schema_pointer, example):
    root = dict(spec)
    root["$ref"] = schema_pointer
    for e in list(Draft202012Validator(root).iter_errors(example))[:3]:
        failures.append("%s: example: %s at %s" % (where, e.message[:300], "/".join(map(str, e.path))))

examples = 0
for path, ops in spec["paths"].items():
    for method, op in ops.items():
        if method not in ("get", "post", "delete", "put", "patch"):
            continue
        where = "%s %s" % (method.upper(), path)
        shown = False
        for status, response in op["responses"].items():
            response, pointer = resolve(response, "#/paths/%s/%s/responses/%s" % (esc(path), method, status))
            content = response.get("content") or {}
            if status.startswith("2") and not content:
                shown = True  # 204: nothing to show
            for media, body in content.items():
                if "example" not in body:
                    continue
                examples += 1
                shown = shown or status.startswith("2")
                if media == "application/json":
                    check_example("%s -> %s" % (where, status), pointer + "/content/" + esc(media) + "/schema", body["example"])
        if not shown:
            failures.append(where + ": no example of its success response")
        request = op.get("requestBody", {}).get("content", {}).get("application/json", {})
        for name, example in request.get("examples", {}).items():
            examples += 1
            check_example("%s request example %s" % (where, name),
                          "#/paths/%s/%s/requestBody/content/application~1json/schema" % (esc(path), method), example["value"])
if examples < 20:
    failures.append("only %d examples" % examples)

for f in failures:
    print(f)
print("%d samples, %d failures" % (len(samples), len(failures)))
sys.exit(1 if failures else 0)
)PY";

struct Sample {
  std::string method, template_path;
  int status;
  std::string content_type, body, request;
};

}  // namespace

TEST_CASE("every response matches openapi.yaml") {
  ServerConfig config;
  config.max_points = 50;
  config.deadline = std::chrono::milliseconds(1);
  config.compile_deadline = std::chrono::milliseconds(60000);  // compile fully, project against 1 ms
  TestServer s(config);
  auto c = s.client();
  std::vector<Sample> samples;
  auto record = [&](const std::string& method, const std::string& templ, const httplib::Result& r,
                    const std::string& request = "") {
    INFO(method << " " << templ << " after " << samples.size() << " samples");
    REQUIRE(r);
    CHECK_FALSE(r->get_header_value("X-Request-Id").empty());
    samples.push_back({method, templ, r->status, r->get_header_value("Content-Type"), r->body, request});
  };
  auto post = [&](const std::string& templ, const std::string& path, const std::string& body,
                  const char* type = "application/json") {
    record("POST", templ, c->Post(path, body, type), body);
  };

  const std::string surface =
      R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}})J";
  const std::string curve =
      R"J({"type":"implicit_curve","equations":["x^2/9+y^2/16+z^2/9-1","x^2+y^2-4*z"],"domain":{"x":[-300,300],"y":[-300,300],"z":[-300,300]}})J";
  const std::string planar =
      R"J({"type":"implicit_curve","equations":["x^2+y^2/4-1"],"domain":{"x":[-3,3],"y":[-3,3]},"constants":{"k":2}})J";
  const std::string param =
      R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","z":"t","domain":{"t":[0,6]}})J";

  for (const char* path : {"/healthz", "/readyz", "/metrics", "/openapi.yaml", "/v1/methods"})
    record("GET", path, c->Get(path));
  for (const auto& def : {surface, curve, planar, param}) post("/v1/geometries", "/v1/geometries", def);
  post("/v1/geometries", "/v1/geometries", surface);  // 200: cached
  const std::string id = json::parse(samples.back().body)["geometry_id"];
  const std::string curve_id = json::parse(samples[6].body)["geometry_id"];
  const std::string geometry = "/v1/geometries/{id}", project = "/v1/geometries/{id}/project";
  record("GET", geometry, c->Get("/v1/geometries/" + id));
  record("GET", geometry, c->Get("/v1/geometries/" + curve_id));
  {
    // Seams declared and found, poles, a closed curve: the closure member of both responses.
    const std::string torus =
        R"J({"type":"parametric_surface","x":"(2+0.5*cos(v))*cos(u)","y":"(2+0.5*cos(v))*sin(u)","z":"0.5*sin(v)",)J"
        R"J("domain":{"u":[0,6.283185307179586],"v":[0,6.283185307179586]},"periodic":["u"]})J";
    const std::string sphere =
        R"J({"type":"parametric_surface","x":"cos(u)*cos(v)","y":"sin(u)*cos(v)","z":"sin(v)",)J"
        R"J("domain":{"u":[0,6.283185307179586],"v":[-1.5707963267948966,1.5707963267948966]}})J";
    const std::string circle =
        R"J({"type":"parametric_curve","x":"cos(t)","y":"sin(t)","domain":{"t":[0,6.283185307179586]},"periodic":["t"]})J";
    for (const auto& def : {torus, sphere, circle}) {
      post("/v1/geometries", "/v1/geometries", def);
      record("GET", geometry,
             c->Get("/v1/geometries/" + json::parse(samples.back().body)["geometry_id"].get<std::string>()));
    }
  }

  const std::string mesh = "/v1/geometries/{id}/mesh";
  const std::string planar_id = json::parse(samples[7].body)["geometry_id"];
  const std::string param_id = json::parse(samples[8].body)["geometry_id"];
  record("GET", mesh, c->Get("/v1/geometries/" + id + "/mesh?resolution=4"));
  record("GET", mesh, c->Get("/v1/geometries/" + curve_id + "/mesh?resolution=16"));
  record("GET", mesh, c->Get("/v1/geometries/" + planar_id + "/mesh?resolution=16&format=json"));
  record("GET", mesh, c->Get("/v1/geometries/" + param_id + "/mesh?resolution=8"));
  record("GET", mesh, c->Get("/v1/geometries/" + id + "/mesh?resolution=3&format=obj"));
  record("GET", mesh, c->Get("/v1/geometries/" + id + "/mesh?resolution=1"));                 // 400
  record("GET", mesh, c->Get("/v1/geometries/" + id + "/mesh?format=ply"));                   // 400
  record("GET", mesh, c->Get("/v1/geometries/00000000000000000000000000000000/mesh"));        // 404
  record("POST", mesh, c->Post("/v1/geometries/" + id + "/mesh", "{}", "application/json"));  // 405

  {
    // An implicit surface (a cone clipped at its apex): definition, answers at the apex, inside
    // and on a box face, its mesh; and a box the surface misses (422 empty_surface).
    post(
        "/v1/geometries", "/v1/geometries",
        R"J({"type":"implicit_surface","equation":"x^2+y^2-z^2","domain":{"x":[-1,1],"y":[-1,1],"z":[0,1]}})J");
    const std::string cone =
        "/v1/geometries/" + json::parse(samples.back().body)["geometry_id"].get<std::string>();
    record("GET", geometry, c->Get(cone));
    post(project, cone + "/project", R"J({"points":[[0,0,-1],[0.5,0.2,0.8],[2,0.5,0.3]]})J");
    post(project, cone + "/project",
         R"J({"point":[0.5,0.2,0.8],"method":"first_order","options":{"trace":true}})J");
    record("GET", mesh, c->Get(cone + "/mesh?resolution=6"));
    post(
        "/v1/geometries", "/v1/geometries",
        R"J({"type":"implicit_surface","equation":"x^2+y^2+z^2+1","domain":{"x":[-1,1],"y":[-1,1],"z":[-1,1]}})J");
  }
  for (const char* page : {"/", "/docs"}) record("GET", page, c->Get(page));
  for (const char* file : {"playground.js", "playground.css", "favicon.svg", "docs.html", "nope.js"})
    record("GET", "/ui/{file}", c->Get(std::string("/ui/") + file));

  const std::string on = "/v1/geometries/" + id + "/project";
  post(project, on, R"J({"point":[1,2,2]})J");
  post(project, on,
       R"J({"points":[[1,2,2],[0,0,3],[5,-1,0.5]],"options":{"all_minima":true,"trace":true}})J");
  post(project, on, R"J({"point":[1,2,2],"method":"gsa","options":{"initial":[0.5,0.7],"trace":true}})J");
  post(project, on, R"J({"point":[100,2,2],"options":{"max_distance":1}})J");
  post(project, on,
       R"J({"points":[[1,2,2],[0,0,3]],"fields":["foot_point","distance","diagnostics.status"]})J");
  post(project, "/v1/geometries/" + curve_id + "/project",
       R"J({"point":[217,273,129],"options":{"all_minima":true}})J");
  {
    std::string big = R"J({"points":[)J";
    for (int i = 0; i < 50; ++i) big += std::string(i ? "," : "") + "[" + std::to_string(i) + ",1,2]";
    post(project, on, big + "]}");  // some points hit the 1 ms deadline
  }
  post("/v1/project", "/v1/project", R"J({"geometry":)J" + planar + R"J(,"points":[[2,2],[0,0]]})J");
  post("/v1/project", "/v1/project",
       R"J({"geometry":)J" + param + R"J(,"point":[1,1,1],"options":{"all_minima":true}})J");

  // The list, and evaluation at parameters.
  record("GET", "/v1/geometries", c->Get("/v1/geometries?limit=2"));
  record("GET", "/v1/geometries", c->Get("/v1/geometries?limit=2&after=" + id));
  record("GET", "/v1/geometries", c->Get("/v1/geometries?limit=0"));  // 400
  const std::string evaluate = "/v1/geometries/{id}/evaluate";
  post(evaluate, "/v1/geometries/" + id + "/evaluate",
       R"J({"parameters":[[0.5,1],[1,2]],"derivatives":2,"normals":true})J");
  post(evaluate, "/v1/geometries/" + param_id + "/evaluate",
       R"J({"parameter":[1],"derivatives":1,"normals":true})J");
  post(evaluate, "/v1/geometries/" + curve_id + "/evaluate", R"J({"parameter":[1]})J");  // 400
  post(evaluate, "/v1/geometries/" + curve_id + "/evaluate",
       R"J({"points":[[1,2,3],[0,0,0]],"derivatives":2,"normals":true})J");
  post(evaluate, "/v1/geometries/" + curve_id + "/evaluate", R"J({"point":[1,2,3]})J");
  {
    const std::string implicit_surface =
        R"J({"type":"implicit_surface","equation":"x^2+y^2+z^2-1","domain":{"x":[-2,2],"y":[-2,2],"z":[-2,2]}})J";
    post("/v1/geometries", "/v1/geometries", implicit_surface);
    const std::string implicit_id = json::parse(samples.back().body)["geometry_id"];
    post(evaluate, "/v1/geometries/" + implicit_id + "/evaluate",
         R"J({"points":[[1,2,3],[0,0,0]],"derivatives":2,"normals":true})J");
    post(evaluate, "/v1/geometries/" + implicit_id + "/evaluate",
         R"J({"points":[[1,2,3]],"parameters":[[1]]})J");
  }
  post(evaluate, "/v1/geometries/00000000000000000000000000000000/evaluate",
       R"J({"parameter":[1]})J");                                         // 404
  record("GET", evaluate, c->Get("/v1/geometries/" + id + "/evaluate"));  // 405

  // Errors of every class.
  post(project, on, R"J({"point":[1,2,)J");                           // 400
  post(project, on, R"J({"points":[[1,2,3],[1,"x",3]]})J");           // 400
  post(project, on, R"J({"point":[1,2,2],"method":"nope"})J");        // 400
  post("/v1/geometries", "/v1/geometries", R"J({"type":"torus"})J");  // 400
  post(
      "/v1/geometries", "/v1/geometries",
      R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1]},"periodic":["w"]})J");  // 400
  post(
      "/v1/geometries", "/v1/geometries",
      R"J({"type":"parametric_surface","x":"u","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1]},"periodic":["u"]})J");  // 422
  post("/v1/project", "/v1/project", R"J({"point":[1,2,3]})J");                                        // 400
  post(project, "/v1/geometries/00000000000000000000000000000000/project", R"J({"point":[1,2,2]})J");  // 404
  record("GET", geometry, c->Get("/v1/geometries/00000000000000000000000000000000"));                  // 404
  record("GET", "/v1/project", c->Get("/v1/project"));                                                 // 405
  record("DELETE", "/healthz", c->Delete("/healthz"));                                                 // 405
  {
    std::string big = R"J({"points":[)J";
    for (int i = 0; i < 51; ++i) big += std::string(i ? "," : "") + "[1,2,3]";
    post(project, on, big + "]}");  // 413
  }
  post(project, on, R"J({"point":[1,2,2]})J", "text/plain");  // 415
  post("/v1/geometries", "/v1/geometries",
       R"J({"type":"parametric_surface","x":"u+","y":"v","z":"0","domain":{"u":[0,1],"v":[0,1]}})J");  // 422
  post(
      "/v1/project", "/v1/project",
      R"J({"geometry":{"type":"parametric_curve","x":"t","y":"t","domain":{"t":[1,0]}},"point":[1,2]})J");  // 422
  record("DELETE", geometry, c->Delete("/v1/geometries/" + id));  // 204
  record("DELETE", geometry, c->Delete("/v1/geometries/" + id));  // 404

  {
    // With API keys and a rate limit: 401 (no key, an unknown one), 403 (a key without the
    // scope), 429 (the key's points spent).
    const std::string keys_file = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                                  "/footpoint_openapi_keys_" + std::to_string(s.port());
    auto hex = [](const std::string& secret) {
      std::string h;
      char buf[3];
      for (const unsigned char byte : sha256(secret)) {
        std::snprintf(buf, sizeof buf, "%02x", byte);
        h += buf;
      }
      return h;
    };
    std::ofstream(keys_file) << "reader project " << hex("readsecret") << "\n";
    ServerConfig keyed_config;
    keyed_config.api_keys = keys_file;
    keyed_config.rate_limit = 1;
    keyed_config.rate_burst = 3;
    TestServer keyed(keyed_config);
    std::remove(keys_file.c_str());
    auto k = keyed.client();
    const httplib::Headers reader{{"Authorization", "Bearer readsecret"}};
    record("GET", "/v1/methods", k->Get("/v1/methods"));
    record("GET", "/v1/methods", k->Get("/v1/methods", {{"Authorization", "Bearer nosuchkey"}}));
    record("GET", "/metrics", k->Get("/metrics", reader));
    record("GET", "/metrics", k->Get("/metrics"));
    record("POST", "/v1/geometries", k->Post("/v1/geometries", reader, planar, "application/json"), planar);
    const std::string inline_body = R"J({"geometry":)J" + planar + R"J(,"points":[[2,2],[0,0]]})J";
    record("POST", "/v1/project", k->Post("/v1/project", reader, inline_body, "application/json"),
           inline_body);
    record("POST", "/v1/project", k->Post("/v1/project", reader, inline_body, "application/json"),
           inline_body);
    CHECK(samples.back().status == 429);
  }

  // 503 while shutting down: what a request that arrives on an open connection meanwhile gets
  // (the idle connections themselves are closed at once, so the Api answers it here).
  s.server().shutdown();
  const ApiResponse down = s.server().api().handle(match_route("GET", "/readyz"), "GET", "");
  samples.push_back({"GET", "/readyz", down.status, down.content_type, down.body, ""});
  CHECK(down.status == 503);

  json out = json::array();
  for (const auto& x : samples)
    out.push_back({{"method", x.method},
                   {"template", x.template_path},
                   {"status", x.status},
                   {"content_type", x.content_type},
                   {"body", x.body},
                   {"request", x.request}});
  const std::string dir = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
  const std::string samples_file = dir + "/footpoint_openapi_samples_" + std::to_string(s.port()) + ".json";
  const std::string script_file = dir + "/footpoint_openapi_check_" + std::to_string(s.port()) + ".py";
  std::ofstream(samples_file) << out.dump();
  std::ofstream(script_file) << kValidator;
  const std::string command =
      "/usr/bin/python3 " + script_file + " " FOOTPOINT_SOURCE_DIR "/openapi.yaml " + samples_file + " 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) output += buf;
  const int status = pclose(pipe);
  INFO(output);
  CHECK(status == 0);
  CHECK(output.find(std::to_string(samples.size()) + " samples, 0 failures") != std::string::npos);
  std::remove(samples_file.c_str());
  std::remove(script_file.c_str());
}
