// The API's routes: path templates, the methods each allows, and matching a request to one.
#pragma once
#include <string_view>

namespace footpoint::server {

enum class Route {
  healthz,            // GET /healthz
  readyz,             // GET /readyz
  metrics,            // GET /metrics
  openapi,            // GET /openapi.yaml
  methods,            // GET /v1/methods
  geometries,         // GET (the list), POST /v1/geometries
  geometry,           // GET, DELETE /v1/geometries/{id}
  geometry_project,   // POST /v1/geometries/{id}/project
  geometry_mesh,      // GET /v1/geometries/{id}/mesh
  geometry_evaluate,  // POST /v1/geometries/{id}/evaluate
  project,            // POST /v1/project
  ui_playground,      // GET / (the geometry playground)
  ui_docs,            // GET /docs (the API reference)
  ui_asset,           // GET /ui/{file} (the pages' scripts, styles, three.js)
  none,               // no such path
};
inline constexpr int kRouteCount = static_cast<int>(Route::none) + 1;

// The path template ("/v1/geometries/{id}/project"); "unmatched" for Route::none.
const char* route_template(Route route);

struct RouteMatch {
  Route route = Route::none;
  std::string_view id;  // the {id} or {file} segment, when the template has one

  bool method_allowed = false;  // HEAD is allowed wherever GET is
  const char* allow = "";       // the Allow header value for a 405
};

RouteMatch match_route(std::string_view method, std::string_view path);

// The routes of the browser pages (--ui off answers them 404).
inline bool is_ui_route(Route r) {
  return r == Route::ui_playground || r == Route::ui_docs || r == Route::ui_asset;
}

// Routes whose work runs on the numerical pool (load shedding applies to them).
inline bool is_compute_route(Route r) {
  return r == Route::geometries || r == Route::geometry_project || r == Route::project ||
         r == Route::geometry_evaluate;
}

}  // namespace footpoint::server
