#include "mesh_response.hpp"

#include <charconv>
#include <cstdint>
#include <vector>

#include "json_writer.hpp"

namespace footpoint::server {

namespace {

// [x0,y0,z0,x1,...]
void flat(JsonWriter& o, const std::vector<Vec3>& points) {
  o.begin_array();
  for (const Vec3& p : points) {
    o.number(p.x);
    o.number(p.y);
    o.number(p.z);
  }
  o.end_array();
}

void flat(JsonWriter& o, const std::vector<double>& values) {
  o.numbers(values.data(), static_cast<int>(values.size()));
}

template <class Integers>
void indices(JsonWriter& o, const Integers& list) {
  o.begin_array();
  for (const auto i : list) o.integer(i);
  o.end_array();
}

void append_integer(std::string& out, long long n) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, n);
  out.append(buf, r.ptr);
}

void append_line(std::string& out, const char* tag, Vec3 x) {
  out += tag;
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    append_shortest(out, x[k]);
  }
  out += '\n';
}

}  // namespace

std::string mesh_json(const CompiledGeometry& geometry, const Mesh& mesh, int resolution) {
  std::string out;
  out.reserve(256 + mesh.vertices.size() * (mesh.num_params + 6) * 20 + mesh.triangles.size() * 24);
  {
    JsonWriter o(out);
    o.begin_object();
    o.key("geometry_id");
    o.string(geometry.id());
    o.key("type");
    o.string(to_string(geometry.definition().type));
    o.key("point_dim");
    o.integer(geometry.point_dim());
    o.key("resolution");
    o.integer(resolution);
    o.key("vertices");
    flat(o, mesh.vertices);
    if (!mesh.normals.empty()) {
      o.key("normals");
      flat(o, mesh.normals);
    }
    if (!mesh.tangents.empty()) {
      o.key("tangents");
      flat(o, mesh.tangents);
    }
    if (mesh.num_params > 0) {
      o.key("parameters");
      flat(o, mesh.parameters);
    }
    o.key("triangles");
    o.begin_array();
    for (const auto& t : mesh.triangles)
      for (const std::int32_t v : t) o.integer(v);
    o.end_array();
    o.key("polylines");
    o.begin_array();
    for (const Polyline& line : mesh.polylines) {
      o.begin_object();
      o.key("vertices");
      indices(o, line.vertices);
      o.key("closed");
      o.boolean(line.closed);
      o.end_object();
    }
    o.end_array();
    o.key("singular_points");
    indices(o, mesh.singular_points);
    o.end_object();
  }
  return out;
}

std::string mesh_obj(const CompiledGeometry& geometry, const Mesh& mesh, int resolution) {
  std::string out;
  out.reserve(256 + mesh.vertices.size() * 120 + mesh.triangles.size() * 40);
  out += "# footpoint mesh of geometry ";
  out += geometry.id();
  out += " (";
  out += to_string(geometry.definition().type);
  out += ", resolution ";
  append_integer(out, resolution);
  out += ")\no footpoint_";
  out += geometry.id();
  out += '\n';
  for (const Vec3& x : mesh.vertices) append_line(out, "v", x);
  for (const Vec3& n : mesh.normals) append_line(out, "vn", n);
  const bool normals = !mesh.normals.empty();
  for (const auto& t : mesh.triangles) {
    out += 'f';
    for (std::int32_t v : t) {
      out += ' ';
      append_integer(out, v + 1);
      if (normals) {
        out += "//";
        append_integer(out, v + 1);
      }
    }
    out += '\n';
  }
  for (const Polyline& line : mesh.polylines) {
    out += 'l';
    for (std::int32_t v : line.vertices) {
      out += ' ';
      append_integer(out, v + 1);
    }
    if (line.closed) {
      out += ' ';
      append_integer(out, line.vertices.front() + 1);
    }
    out += '\n';
  }
  for (std::int32_t v : mesh.singular_points) {
    out += "p ";
    append_integer(out, v + 1);
    out += '\n';
  }
  return out;
}

}  // namespace footpoint::server
