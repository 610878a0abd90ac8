#include "api.hpp"

#include <chrono>
#include <limits>
#include <memory>
#include <new>
#include <vector>

#include "batch/batch.hpp"
#include "evaluate_request.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "json_writer.hpp"
#include "mesh/mesh.hpp"
#include "mesh_request.hpp"
#include "mesh_response.hpp"
#include "openapi_text.hpp"
#include "project_request.hpp"
#include "project_stream.hpp"
#include "query.hpp"
#include "request_log.hpp"
#include "result_json.hpp"
#include "ui_files.hpp"

namespace footpoint::server {

// What the requests being answered take at once (points, estimated bytes), against a limit. A
// request over it gets 503 overloaded (counted in `refused`), unless nothing else is in flight
// (so even one larger than the limit runs, alone) or it takes at most `always` units.
struct InflightBudget {
  std::atomic<std::size_t>& in_flight;
  std::size_t limit;
  const char* unit;  // "points", "bytes"
  const char* flag;
  std::size_t always = 0;
  std::atomic<std::uint64_t>* refused = nullptr;
};

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

ApiResponse json_response(int status, std::string body) {
  ApiResponse r;
  r.status = status;
  r.body = std::move(body);
  return r;
}

// Counts the requests being answered (load shedding reads the count).
struct InFlight {
  explicit InFlight(std::atomic<std::size_t>& n) : n(n) { n.fetch_add(1, std::memory_order_relaxed); }
  ~InFlight() { n.fetch_sub(1, std::memory_order_relaxed); }
  InFlight(const InFlight&) = delete;
  InFlight& operator=(const InFlight&) = delete;
  std::atomic<std::size_t>& n;
};

// Takes `n` units of an InflightBudget for the life of a request, or refuses it (see there).
class Reservation {
 public:
  Reservation(const InflightBudget& budget, std::size_t n) : in_flight_(budget.in_flight), n_(n) {
    std::size_t current = in_flight_.load();
    do {
      if (current != 0 && n > budget.always && current + n > budget.limit) {
        if (budget.refused) budget.refused->fetch_add(1, std::memory_order_relaxed);
        throw ApiError(503, "overloaded",
                       std::string("too many ") + budget.unit + " in progress (" + std::to_string(current) +
                           " + " + std::to_string(n) + " > " + std::to_string(budget.limit) + ", " +
                           budget.flag + "); retry shortly");
      }
    } while (!in_flight_.compare_exchange_weak(current, current + n));
  }
  ~Reservation() { in_flight_.fetch_sub(n_); }
  Reservation(const Reservation&) = delete;
  Reservation& operator=(const Reservation&) = delete;

 private:
  std::atomic<std::size_t>& in_flight_;
  std::size_t n_;
};

// A geometry id is what POST /v1/geometries answers: 32 lower-case hex digits. Anything else is
// a client's mistake (400), not an id that is not held (404: post it again).
void check_geometry_id(std::string_view id, const char* field = "id") {
  bool hex = id.size() == 32, lower_case = true;
  for (const char c : id) {
    const bool digit = c >= '0' && c <= '9', small = c >= 'a' && c <= 'f', capital = c >= 'A' && c <= 'F';
    hex = hex && (digit || small || capital);
    lower_case = lower_case && !capital;
  }
  if (hex && lower_case) return;
  std::string suggestion;
  if (hex)
    for (const char c : id) suggestion += c >= 'A' && c <= 'F' ? static_cast<char>(c - 'A' + 'a') : c;
  throw ApiError(400, "invalid_geometry_id",
                 "'" + std::string(id.substr(0, 80)) + (id.size() > 80 ? "..." : "") +
                     "' is not a geometry id: an id is the 32 lower-case hex digits of the geometry_id that "
                     "POST /v1/geometries answers" +
                     (hex ? " (this one has capitals)" : ""),
                 field, -1, suggestion);
}

void write_method_names(JsonWriter& w, const CompiledGeometry& g) {
  w.begin_array();
  for (const auto& m : g.methods()) w.string(m.name);
  w.end_array();
}

}  // namespace

Api::Api(const ServerConfig& config, GeometryCache& cache, ThreadPool& pool, Metrics& metrics,
         GeometryRegistry* registry)
    : config_(config),
      cache_(cache),
      pool_(pool),
      metrics_(metrics),
      registry_(registry),
      max_inflight_bytes_(config.effective_max_inflight_bytes(0)) {}

namespace {

InflightBudget points_budget(std::atomic<std::size_t>& in_flight, const ServerConfig& config) {
  return {in_flight, config.max_inflight_points, "points", "--max-inflight-points"};
}

}  // namespace

InflightBudget Api::memory_budget() {
  return {in_flight_bytes_,
          max_inflight_bytes_,
          "bytes of memory",
          "--max-inflight-bytes",
          ServerConfig::kAlwaysAdmittedBytes,
          &memory_refusals_};
}

ApiResponse Api::error_response(const ApiError& error) {
  ApiResponse r = json_response(error.status, error_body(error));
  r.error_code = error.code;
  if (error.code == "overloaded" || error.code == "registry_unavailable") r.retry_after_s = 1;
  if (error.retry_after_s > 0) r.retry_after_s = error.retry_after_s;
  return r;
}

Metrics::Gauges Api::gauges() const {
  Metrics::Gauges g;
  g.cache = cache_.stats();
  g.worker_threads = pool_.size();
  g.worker_queue = pool_.queued();
  g.in_flight = in_flight();
  g.in_flight_points = in_flight_points();
  g.in_flight_bytes = in_flight_bytes_.load(std::memory_order_relaxed);
  g.max_inflight_bytes = max_inflight_bytes_;
  g.memory_refusals = memory_refusals_.load(std::memory_order_relaxed);
  g.shutting_down = shutting_down();
  g.registry = registry_ ? &registry_->metrics() : nullptr;
  return g;
}

ApiResponse Api::handle(const RouteMatch& match, std::string_view method, std::string_view body,
                        std::string_view query, const Caller& caller, const RequestFormat& format) {
  try {
    switch (match.route) {
      case Route::healthz:
        return health();
      case Route::readyz:
        return ready();
      case Route::metrics:
        return metrics();
      case Route::openapi:
        return openapi();
      case Route::methods:
        return methods();
      case Route::geometries: {
        if (method != "POST") return list_geometries(query);  // HEAD: the HTTP layer drops the body
        InFlight counted(in_flight_);
        return create_geometry(body, caller);
      }
      case Route::geometry:
        if (method == "DELETE") return delete_geometry(match.id, caller);
        return get_geometry(match.id);  // HEAD: the HTTP layer drops the body
      case Route::geometry_project: {
        InFlight counted(in_flight_);
        return project(match.id, body, query, format, caller);
      }
      case Route::geometry_mesh: {
        InFlight counted(in_flight_);
        return mesh(match.id, query);
      }
      case Route::geometry_evaluate: {
        InFlight counted(in_flight_);
        return evaluate(match.id, body, caller);
      }
      case Route::project: {
        InFlight counted(in_flight_);
        return project({}, body, query, format, caller);
      }
      case Route::ui_playground:
      case Route::ui_docs:
      case Route::ui_asset:
        return ui(match);
      case Route::none:
        break;
    }
    return error_response(ApiError(404, "route_not_found", "no such route (see GET /openapi.yaml)"));
  } catch (const ApiError& e) {
    return error_response(e);
  } catch (const std::bad_alloc&) {
    log_event(spdlog::level::err, "out of memory while answering a request");
    return error_response(
        ApiError(503, "overloaded", "the server ran out of memory for this request; retry later"));
  } catch (const std::exception& e) {
    log_event(spdlog::level::err, "internal error", {{"what", e.what()}});
    return error_response(ApiError(500, "internal_error", "internal error"));
  }
}

ApiResponse Api::health() const { return json_response(200, R"({"status":"ok"})"); }

ApiResponse Api::ready() const {
  if (shutting_down()) return error_response(ApiError(503, "shutting_down", "the server is shutting down"));
  return json_response(200, R"({"status":"ready"})");
}

ApiResponse Api::metrics() const {
  ApiResponse r;
  r.content_type = "text/plain; version=0.0.4; charset=utf-8";
  r.body = metrics_.render(gauges());
  return r;
}

ApiResponse Api::openapi() const {
  ApiResponse r;
  r.content_type = "application/yaml";
  r.body = std::string(openapi_text());
  return r;
}

ApiResponse Api::methods() {
  std::lock_guard lock(methods_mutex_);
  if (methods_body_.empty()) {
    JsonWriter w;
    w.begin_object();
    w.key("geometry_types");
    w.begin_array();
    for (const GeometryType type : kGeometryTypes) {
      w.begin_object();
      w.key("type");
      w.string(to_string(type));
      w.key("methods");
      w.begin_array();
      for (const MethodInfo& m : methods_of(type)) {
        w.begin_object();
        w.key("name");
        w.string(m.name);
        w.key("description");
        w.string(m.description);
        w.key("paper");
        w.string(m.paper);
        w.key("citations");
        w.begin_array();
        for (const auto citation : m.citations)
          if (!citation.empty()) w.string(citation);
        w.end_array();
        w.key("options");
        w.begin_array();
        for (std::uint32_t bit = 0; bit < kMethodOptionCount; ++bit)
          if (m.options & (1u << bit)) w.string(option_name(bit));
        w.end_array();
        w.key("statuses");
        w.begin_array();
        for (unsigned s = 0; s < static_cast<unsigned>(Metrics::kStatusCount); ++s)
          if (m.statuses & (1u << s)) w.string(to_string(static_cast<Status>(s)));
        w.end_array();
        w.end_object();
      }
      w.end_array();
      w.end_object();
    }
    w.end_array();
    w.end_object();
    methods_body_ = w.take();
  }
  return json_response(200, methods_body_);
}

formula::CompileLimits Api::compile_limits() const {
  formula::CompileLimits limits;
  limits.max_formula_length = config_.max_formula_length;
  limits.deadline = std::chrono::steady_clock::now() +
                    (config_.compile_deadline.count() > 0 ? config_.compile_deadline : config_.deadline);
  return limits;
}

GeometryCache::Lookup Api::compile(const GeometryDefinition& def, const std::string& field_prefix,
                                   const Caller& caller) {
  try {
    auto lookup = cache_.get_or_compile(def, compile_limits(), caller.key);
    if (lookup.compiled) metrics_.observe_compile(lookup.compile_time.count());
    return lookup;
  } catch (const GeometryError& e) {
    // The cache is full of other keys' geometries and this one would take more than the key's
    // share: storage, not the definition, is what is missing.
    const int status = e.code == "cache_share_exceeded" ? 507 : 422;
    throw ApiError(status, e.code, e.what(), e.field.empty() ? std::string() : field_prefix + e.field,
                   e.position, e.suggestion);
  }
}

namespace {

// posted_by: the API key that posted a held geometry, null when none is recorded (no keys).
void write_posted_by(JsonWriter& w, const std::string& owner) {
  w.key("posted_by");
  if (owner.empty())
    w.null();
  else
    w.string(owner);
}

}  // namespace

std::shared_ptr<const CompiledGeometry> Api::held_geometry(std::string_view id) {
  const std::string key(id);
  if (auto g = cache_.find(key)) {
    if (registry_) registry_->note_use(key);
    return g;
  }
  if (!registry_) return nullptr;
  try {
    const auto lookup = registry_->load(key, compile_limits());
    if (lookup.compiled) metrics_.observe_compile(lookup.compile_time.count());
    return lookup.geometry;
  } catch (const RegistryUnavailable& e) {
    // Not 404: whether the id exists is not known while the registry cannot be asked.
    throw ApiError(503, "registry_unavailable",
                   "geometry " + key + " is not held by this replica and the shared registry cannot be " +
                       "reached; retry shortly, or use POST /v1/project with the definition inline",
                   "id");
  } catch (const GeometryError& e) {
    throw ApiError(422, e.code, std::string("the stored definition does not compile here: ") + e.what(),
                   e.field, e.position, e.suggestion);
  }
}

std::shared_ptr<const CompiledGeometry> Api::geometry_by_id(std::string_view id, const char* alternative) {
  check_geometry_id(id);
  auto geometry = held_geometry(id);
  if (!geometry)
    throw ApiError(404, "geometry_not_found",
                   "geometry " + std::string(id) + " is not held (evicted, deleted, or never posted): " +
                       "POST its definition to /v1/geometries again (the id stays the same)" + alternative,
                   "id");
  return geometry;
}

ApiResponse Api::create_geometry(std::string_view body, const Caller& caller) {
  GeometryDefinition def;
  try {
    JsonReader reader(body);
    def = read_geometry(reader, "");
    at_field("body", [&] { reader.finish(); });
  } catch (const ApiError& e) {
    throw unless_malformed(body, e);
  }
  const auto lookup = compile(def, "", caller);
  const CompiledGeometry& g = *lookup.geometry;
  JsonWriter w;
  w.begin_object();
  w.key("geometry_id");
  w.string(g.id());
  w.key("type");
  w.string(to_string(g.definition().type));
  w.key("point_dim");
  w.integer(g.point_dim());
  w.key("num_params");
  w.integer(g.num_params());
  w.key("methods");
  write_method_names(w, g);
  w.key("memory_bytes");
  w.integer(static_cast<long long>(g.memory_bytes()));
  w.key("compile_ms");
  w.number(lookup.compile_time.count() * 1e3);
  write_closure(w, g);
  // Whether every replica can now answer the id: "stored" in the shared registry, "not_stored"
  // (the registry is unavailable: this replica only, stored when the registry is back), or
  // "off" (no registry configured).
  w.key("registry");
  w.string(!registry_ ? "off" : registry_->store(g, caller.key) ? "stored" : "not_stored");
  w.end_object();
  ApiResponse r = json_response(lookup.compiled ? 201 : 200, w.take());
  r.location = "/v1/geometries/" + g.id();
  return r;
}

ApiResponse Api::list_geometries(std::string_view query) {
  std::size_t limit = kDefaultListLimit;
  std::string after;
  for (const auto& [name, value] : query_parameters(query, {"limit", "after"})) {
    if (name == "limit") {
      limit = static_cast<std::size_t>(query_integer(name, value, 1, kMaxListLimit));
    } else {
      check_geometry_id(value, "after");
      after = value;
    }
  }
  const GeometryCache::Page page = cache_.page(after, limit);
  JsonWriter w(128 + page.held.size() * 160);
  w.begin_object();
  w.key("geometries");
  w.begin_array();
  for (const auto& [g, stats] : page.held) {
    w.begin_object();
    w.key("geometry_id");
    w.string(g->id());
    w.key("type");
    w.string(to_string(g->definition().type));
    w.key("point_dim");
    w.integer(g->point_dim());
    w.key("num_params");
    w.integer(g->num_params());
    w.key("memory_bytes");
    w.integer(static_cast<long long>(stats.bytes));
    w.key("hits");
    w.integer(static_cast<long long>(stats.hits));
    write_posted_by(w, stats.owner);
    w.end_object();
  }
  w.end_array();
  w.key("held");
  w.integer(static_cast<long long>(cache_.stats().size));
  w.key("next");
  if (page.more)
    w.string(page.held.back().geometry->id());
  else
    w.null();
  w.end_object();
  return json_response(200, w.take());
}

ApiResponse Api::get_geometry(std::string_view id) {
  const auto g = geometry_by_id(id);
  const auto entry = cache_.entry_stats(g->id());
  JsonWriter w;
  w.begin_object();
  w.key("geometry_id");
  w.string(g->id());
  w.key("definition");
  write_geometry(w, g->definition());
  w.key("point_dim");
  w.integer(g->point_dim());
  w.key("num_params");
  w.integer(g->num_params());
  w.key("methods");
  write_method_names(w, *g);
  write_closure(w, *g);
  write_posted_by(w, entry ? entry->owner : std::string());
  w.key("cache");
  w.begin_object();
  w.key("hits");
  w.integer(entry ? static_cast<long long>(entry->hits) : 0);
  w.key("memory_bytes");
  w.integer(static_cast<long long>(g->memory_bytes()));
  w.end_object();
  w.end_object();
  return json_response(200, w.take());
}

ApiResponse Api::delete_geometry(std::string_view id, const Caller& caller) {
  check_geometry_id(id);
  bool held = false;
  std::string posted_by;
  if (const auto entry = cache_.entry_stats(std::string(id))) posted_by = entry->owner;
  if (registry_) {
    try {
      const auto erased = registry_->erase(std::string(id));
      held = erased.held;
      if (posted_by.empty()) posted_by = erased.posted_by;
    } catch (const RegistryUnavailable&) {
      throw ApiError(503, "registry_unavailable",
                     "the shared registry cannot be reached, so geometry " + std::string(id) +
                         " cannot be deleted everywhere; nothing was deleted: retry shortly",
                     "id");
    }
  }
  held = cache_.erase(std::string(id)) || held;
  // The audit line: who deleted what (the log line's ts says when) and who had posted it, whether or
  // not it was held.
  log_event(spdlog::level::info, "geometry deleted",
            {{"key", caller.key.empty() ? std::string_view("-") : caller.key},
             {"geometry_id", id},
             {"held", held},
             {"posted_by", posted_by.empty() ? std::string_view("-") : std::string_view(posted_by)}});
  if (!held) throw ApiError(404, "geometry_not_found", "geometry " + std::string(id) + " is not held", "id");
  ApiResponse r;
  r.status = 204;
  r.content_type.clear();
  return r;
}

ApiResponse Api::project(std::string_view id, std::string_view body, std::string_view query,
                         const RequestFormat& format, const Caller& caller) {
  const bool inline_geometry = id.empty();
  const bool binary_in = format.content_type == "application/octet-stream";
  const AnswerFormat answer = answer_format(format.accept);
  const bool streamed = answer != AnswerFormat::json;
  if (binary_in && inline_geometry)
    throw ApiError(415, "unsupported_media_type",
                   "POST /v1/project takes JSON (the definition travels with the points): for binary points, "
                   "POST the definition to /v1/geometries, then the points to /v1/geometries/{id}/project");
  std::shared_ptr<const CompiledGeometry> geometry;
  if (!inline_geometry) {
    geometry = geometry_by_id(id, ", or use POST /v1/project with the definition inline");
  }
  // A streamed answer holds one window of results at a time: --max-points bounds the batches held
  // whole, the body's size (--max-body-bytes) a stream.
  const std::size_t max_points = streamed ? std::numeric_limits<std::size_t>::max() : config_.max_points;
  // A body still to be read is read whole unless it is a stream's binary points.
  std::string whole_body;
  if (format.source && !(binary_in && streamed)) {
    whole_body.reserve(format.source->length);
    if (!format.source->read([&](const char* data, std::size_t size) {
          whole_body.append(data, size);
          return true;
        }))
      throw body_incomplete(whole_body.size(), format.source->length);
    body = whole_body;
  }
  const bool read_as_sent = format.source && binary_in && streamed;
  ProjectRequest request =
      read_as_sent
          ? read_binary_project_options(query, geometry->point_dim(), format.source->length, max_points)
      : binary_in ? read_binary_project_request(body, query, geometry->point_dim(), max_points)
                  : read_project_request(body, inline_geometry, max_points);
  if (inline_geometry) geometry = compile(*request.geometry, "geometry.", caller).geometry;
  const GeometryMethod method = check_project_request(request, *geometry);
  if (caller.charge) caller.charge(request.count);

  if (streamed) {
    if (request.single)
      throw ApiError(
          406, "not_acceptable",
          "a single point is answered in JSON; stream a batch (\"points\") or ask for application/json",
          "point");
    // One window's results and answer, and the binary body read ahead of them.
    const std::size_t window = std::min(request.count, kStreamWindow);
    auto memory = std::make_shared<Reservation>(
        memory_budget(),
        window * ServerConfig::kBytesPerPoint +
            (read_as_sent ? kStreamAhead * window * binary_record_bytes(request, geometry->point_dim()) : 0));
    auto stream = std::make_shared<ProjectStream>(geometry, method);
    stream->format = answer;
    if (answer == AnswerFormat::binary)
      stream->layout =
          binary_layout(request.fields, request.fields_given, geometry->point_dim(), geometry->num_params());
    if (read_as_sent) {
      // the first window is read and checked before the answer starts: what is wrong there is
      // answered with its status (project_stream.hpp tells what a later fault answers)
      const std::size_t record = binary_record_bytes(request, geometry->point_dim());
      stream->body = std::make_shared<StreamedBody>(*format.source, record, kStreamWindow * record,
                                                    kStreamAhead * kStreamWindow * record);
      std::string raw;
      const std::size_t first = stream->body->wait_first(raw);
      std::vector<double> points(first * static_cast<std::size_t>(geometry->point_dim()));
      decode_points(request, raw.data(), first, points.data());
      check_finite(request, 0, points.data(), first);
      if (first < std::min(request.count, kStreamWindow))
        throw body_incomplete(stream->body->bytes_read(), format.source->length);
    }
    stream->request = std::move(request);
    stream->deadline = Clock::now() + config_.deadline;
    stream->pool = &pool_;
    stream->tenant = std::string(caller.key);
    stream->metrics = &metrics_;
    stream->client_gone = caller.client_gone;
    // The stream runs after this returns: it keeps its own counts of requests and points in flight
    // (one window of points).
    auto reserved = std::make_shared<Reservation>(points_budget(in_flight_points_, config_),
                                                  std::min(stream->request.count, kStreamWindow));
    auto counted = std::make_shared<InFlight>(in_flight_);
    ApiResponse r;
    r.points = stream->request.count;
    if (answer == AnswerFormat::binary) {
      r.content_type = "application/octet-stream";
      r.headers.emplace_back("X-Footpoint-Record", stream->layout.describe());
      r.headers.emplace_back("X-Footpoint-Record-Bytes", std::to_string(stream->layout.record_bytes()));
    } else {
      r.content_type = "application/x-ndjson";
    }
    if (stream->body) r.release = [body = stream->body] { body->stop(); };
    r.stream = [stream, reserved, memory, counted](const ApiResponse::Write& write) {
      try {
        return run_stream(*stream, write);
      } catch (const std::exception& e) {
        // the status is sent: the answer is cut, which the client sees
        log_event(spdlog::level::err, "a streamed projection failed", {{"what", e.what()}});
        return false;
      }
    };
    return r;
  }

  const Reservation reserved(points_budget(in_flight_points_, config_), request.count);
  const Reservation memory(memory_budget(), request.count * ServerConfig::kBytesPerPoint);
  BatchRequest batch{method};
  batch.options = request.options;
  batch.points = request.coords.data();
  batch.count = request.count;
  batch.initials = std::move(request.initials);
  const auto solve_start = Clock::now();
  batch.deadline = solve_start + config_.deadline;
  batch.tenant = std::string(caller.key);
  batch.cancelled = caller.client_gone;
  std::vector<ProjectionResult> results;
  try {
    results = project_batch(pool_, batch);
  } catch (const BatchCancelled& cancelled) {
    metrics_.add_cancelled(cancelled.dropped());
    log_event(spdlog::level::info, "batch cancelled: the client closed the connection",
              {{"points", request.count}, {"done", cancelled.done()}, {"dropped", cancelled.dropped()}});
    throw ApiError(
        499, "client_closed_request",
        "the client closed the connection before the answer: " + std::to_string(cancelled.dropped()) +
            " of the " + std::to_string(request.count) + " points were not projected");
  }
  const double elapsed_ms = ms_since(solve_start);

  std::array<std::uint64_t, Metrics::kStatusCount> by_status{};
  for (const auto& r : results) ++by_status[static_cast<std::size_t>(reported_status(r))];
  metrics_.add_projections(by_status);

  ApiResponse r = json_response(200, project_response(geometry->id(), results, request.single, request.fields,
                                                      elapsed_ms, request.deviation));
  r.points = results.size();
  return r;
}

ApiResponse Api::mesh(std::string_view id, std::string_view query) {
  const auto geometry = geometry_by_id(id);
  MeshRequest request = read_mesh_request(query, config_.max_mesh_resolution);
  if (request.resolution == 0)
    request.resolution =
        std::min(config_.max_mesh_resolution,
                 geometry->num_params() == 2 || geometry->definition().type == GeometryType::implicit_surface
                     ? kDefaultSurfaceResolution
                     : kDefaultCurveResolution);
  // A surface's mesh has (resolution + 1)^2 vertices at most, a curve's resolution + 1: the mesh,
  // its text and the answer held at once.
  const auto side = static_cast<std::size_t>(request.resolution) + 1;
  const bool surface =
      geometry->num_params() == 2 || geometry->definition().type == GeometryType::implicit_surface;
  const Reservation memory(memory_budget(),
                           (surface ? side * side : side) * ServerConfig::kMeshBytesPerVertex);
  const Mesh mesh = mesh_geometry(*geometry, MeshOptions{request.resolution});
  ApiResponse r;
  if (request.format == MeshFormat::obj) {
    r.content_type = "model/obj";
    r.body = mesh_obj(*geometry, mesh, request.resolution);
    r.headers.emplace_back("Content-Disposition",
                           "attachment; filename=\"footpoint-" + geometry->id() + ".obj\"");
  } else {
    r.body = mesh_json(*geometry, mesh, request.resolution);
  }
  return r;
}

ApiResponse Api::evaluate(std::string_view id, std::string_view body, const Caller& caller) {
  const auto geometry = geometry_by_id(id);
  const EvaluateRequest request = read_evaluate_request(body, config_.max_points);
  if (caller.charge) caller.charge(request.count);
  const Reservation reserved(points_budget(in_flight_points_, config_), request.count);
  const Reservation memory(memory_budget(), request.count * ServerConfig::kBytesPerPoint);
  ApiResponse r = json_response(200, evaluate_response(*geometry, request));
  r.points = request.count;
  return r;
}

ApiResponse Api::ui(const RouteMatch& match) const {
  if (!config_.ui) throw ApiError(404, "route_not_found", "the browser pages are turned off (--ui off)");
  const std::string_view name = match.route == Route::ui_playground ? "index.html"
                                : match.route == Route::ui_docs     ? "docs.html"
                                                                    : match.id;
  for (const UiFile& file : ui_files())
    if (file.name == name) {
      ApiResponse r;
      r.content_type = std::string(file.content_type);
      r.body = std::string(file.text);
      // Scripts, styles and requests of the same origin only: no inline script, nothing external.
      r.headers.emplace_back("Content-Security-Policy", "default-src 'self'");
      r.headers.emplace_back("X-Content-Type-Options", "nosniff");
      return r;
    }
  throw ApiError(404, "route_not_found", "no file /ui/" + std::string(name));
}

}  // namespace footpoint::server
