// GET /v1/geometries/{id}/mesh?resolution=N&format=json|obj: the query, read and checked.
#pragma once
#include <string_view>

namespace footpoint::server {

enum class MeshFormat { json, obj };

struct MeshRequest {
  int resolution = 0;  // 0: the geometry's default (kDefaultSurfaceResolution, kDefaultCurveResolution)
  MeshFormat format = MeshFormat::json;
};

// Without a resolution: a surface gets 64 cells along its larger direction (~8,000 triangles),
// a curve 512 segments.
inline constexpr int kDefaultSurfaceResolution = 64;
inline constexpr int kDefaultCurveResolution = 512;

// Reads `query` (the target after '?', percent-encoded). Throws ApiError 400: unknown_field for
// a parameter other than resolution and format, duplicate_field, wrong_type (resolution not an
// integer), number_out_of_range (resolution outside [2, max_resolution]), unknown_format.
MeshRequest read_mesh_request(std::string_view query, int max_resolution);

}  // namespace footpoint::server
