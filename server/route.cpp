#include "route.hpp"

namespace footpoint::server {

const char* route_template(Route route) {
  switch (route) {
    case Route::healthz:
      return "/healthz";
    case Route::readyz:
      return "/readyz";
    case Route::metrics:
      return "/metrics";
    case Route::openapi:
      return "/openapi.yaml";
    case Route::methods:
      return "/v1/methods";
    case Route::geometries:
      return "/v1/geometries";
    case Route::geometry:
      return "/v1/geometries/{id}";
    case Route::geometry_project:
      return "/v1/geometries/{id}/project";
    case Route::geometry_mesh:
      return "/v1/geometries/{id}/mesh";
    case Route::geometry_evaluate:
      return "/v1/geometries/{id}/evaluate";
    case Route::project:
      return "/v1/project";
    case Route::ui_playground:
      return "/";
    case Route::ui_docs:
      return "/docs";
    case Route::ui_asset:
      return "/ui/{file}";
    case Route::none:
      return "unmatched";
  }
  return "unmatched";
}

RouteMatch match_route(std::string_view method, std::string_view path) {
  RouteMatch m;
  const bool get = method == "GET" || method == "HEAD";
  auto allow = [&](bool allowed, const char* allow_header) {
    m.method_allowed = allowed;
    m.allow = allow_header;
  };
  if (path == "/" || path == "/docs") {
    m.route = path == "/" ? Route::ui_playground : Route::ui_docs;
    allow(get, "GET, HEAD");
  } else if (constexpr std::string_view ui = "/ui/";
             path.substr(0, ui.size()) == ui && path.size() > ui.size()) {
    m.route = Route::ui_asset;
    m.id = path.substr(ui.size());
    allow(get, "GET, HEAD");
  } else if (path == "/healthz") {
    m.route = Route::healthz;
    allow(get, "GET, HEAD");
  } else if (path == "/readyz") {
    m.route = Route::readyz;
    allow(get, "GET, HEAD");
  } else if (path == "/metrics") {
    m.route = Route::metrics;
    allow(get, "GET, HEAD");
  } else if (path == "/openapi.yaml") {
    m.route = Route::openapi;
    allow(get, "GET, HEAD");
  } else if (path == "/v1/methods") {
    m.route = Route::methods;
    allow(get, "GET, HEAD");
  } else if (path == "/v1/project") {
    m.route = Route::project;
    allow(method == "POST", "POST");
  } else if (path == "/v1/geometries") {
    m.route = Route::geometries;
    allow(get || method == "POST", "GET, HEAD, POST");
  } else if (constexpr std::string_view prefix = "/v1/geometries/"; path.substr(0, prefix.size()) == prefix) {
    std::string_view rest = path.substr(prefix.size());
    constexpr std::string_view project = "/project", mesh = "/mesh", evaluate = "/evaluate";
    const auto slash = rest.find('/');
    if (slash == std::string_view::npos) {
      if (rest.empty()) return m;
      m.route = Route::geometry;
      m.id = rest;
      allow(get || method == "DELETE", "GET, HEAD, DELETE");
    } else if (slash > 0 && rest.substr(slash) == project) {
      m.route = Route::geometry_project;
      m.id = rest.substr(0, slash);
      allow(method == "POST", "POST");
    } else if (slash > 0 && rest.substr(slash) == mesh) {
      m.route = Route::geometry_mesh;
      m.id = rest.substr(0, slash);
      allow(get, "GET, HEAD");
    } else if (slash > 0 && rest.substr(slash) == evaluate) {
      m.route = Route::geometry_evaluate;
      m.id = rest.substr(0, slash);
      allow(method == "POST", "POST");
    }
  }
  return m;
}

}  // namespace footpoint::server
