#include "mesh_request.hpp"

#include <string>

#include "api_error.hpp"
#include "query.hpp"

namespace footpoint::server {

MeshRequest read_mesh_request(std::string_view query, int max_resolution) {
  MeshRequest request;
  for (const auto& [name, value] : query_parameters(query, {"resolution", "format"})) {
    if (name == "resolution") {
      request.resolution = static_cast<int>(query_integer(name, value, 2, max_resolution));
    } else if (value == "json") {
      request.format = MeshFormat::json;
    } else if (value == "obj") {
      request.format = MeshFormat::obj;
    } else {
      throw ApiError(400, "unknown_format", "format must be json or obj, got '" + value + "'", name);
    }
  }
  return request;
}

}  // namespace footpoint::server
