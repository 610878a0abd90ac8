#include "mesh_response.hpp"

#include <charconv>
#include <cstdint>
#include <vector>

#include "json_writer.hpp"

namespace footpoint::server {

namespace {

// [x0,y0,z0,x1,...]
void flat(JsonAppender& o, const std::vector<Vec3>& points) {
  o.literal("[");
  for (std::size_t i = 0; i < points.size(); ++i) {
    o.literal(i ? "," : "");
    o.number(points[i].x);
    o.literal(",");
    o.number(points[i].y);
    o.literal(",");
    o.number(points[i].z);
  }
  o.literal("]");
}

void flat(JsonAppender& o, const std::vector<double>& values) {
  o.literal("[");
  for (std::size_t i = 0; i < values.size(); ++i) {
    o.literal(i ? "," : "");
    o.number(values[i]);
  }
  o.literal("]");
}

void indices(JsonAppender& o, const std::vector<std::int32_t>& list) {
  o.literal("[");
  for (std::size_t i = 0; i < list.size(); ++i) {
    o.literal(i ? "," : "");
    o.integer(list[i]);
  }
  o.literal("]");
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
    JsonAppender o(out);
    o.literal("{\"geometry_id\":");
    o.string(geometry.id());
    o.literal(",\"type\":");
    o.string(to_string(geometry.definition().type));
    o.literal(",\"point_dim\":");
    o.integer(geometry.point_dim());
    o.literal(",\"resolution\":");
    o.integer(resolution);
    o.literal(",\"vertices\":");
    flat(o, mesh.vertices);
    if (!mesh.normals.empty()) {
      o.literal(",\"normals\":");
      flat(o, mesh.normals);
    }
    if (!mesh.tangents.empty()) {
      o.literal(",\"tangents\":");
      flat(o, mesh.tangents);
    }
    if (mesh.num_params > 0) {
      o.literal(",\"parameters\":");
      flat(o, mesh.parameters);
    }
    o.literal(",\"triangles\":[");
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const auto& t = mesh.triangles[i];
      o.literal(i ? "," : "");
      o.integer(t[0]);
      o.literal(",");
      o.integer(t[1]);
      o.literal(",");
      o.integer(t[2]);
    }
    o.literal("],\"polylines\":[");
    for (std::size_t i = 0; i < mesh.polylines.size(); ++i) {
      o.literal(i ? ",{\"vertices\":" : "{\"vertices\":");
      indices(o, mesh.polylines[i].vertices);
      o.literal(mesh.polylines[i].closed ? ",\"closed\":true}" : ",\"closed\":false}");
    }
    o.literal("],\"singular_points\":");
    indices(o, mesh.singular_points);
    o.literal("}");
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
