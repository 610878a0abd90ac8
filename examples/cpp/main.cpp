// Projecting points onto a surface and a curve in-process: compile a definition once, look its
// method up by name, project. Build it against the installed package (see CMakeLists.txt).
#include <array>
#include <cstdio>
#include <vector>

#include "footpoint.hpp"

using namespace footpoint;

namespace {

void print(const char* what, const ProjectionResult& r) {
  std::printf("%s: foot %.17g %.17g %.17g, distance %.17g, %s\n", what, r.foot[0], r.foot[1], r.foot[2],
              r.distance, to_string(r.summary.status));
}

}  // namespace

int main() {
  // A torus with radii 2 and 0.5: the nearest point to (3, 0, 0) is (2.5, 0, 0).
  GeometryDefinition torus;
  torus.type = GeometryType::parametric_surface;
  torus.formulas = {{"x", "(2+0.5*cos(v))*cos(u)"}, {"y", "(2+0.5*cos(v))*sin(u)"}, {"z", "0.5*sin(v)"}};
  torus.domain = {{"u", {0.0, 6.283185307179586}}, {"v", {0.0, 6.283185307179586}}};
  const std::shared_ptr<const CompiledGeometry> surface = compile_geometry(torus);  // throws GeometryError
  const std::array<double, 3> p{3.0, 0.0, 0.0};
  print("surface auto", surface->project(p.data(), "auto", Options{}).value());

  // The unit circle as a planar parametric curve, with several points in one batch on a pool.
  GeometryDefinition circle;
  circle.type = GeometryType::parametric_curve;
  circle.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}};
  circle.domain = {{"t", {-3.0, 3.0}}};
  const std::shared_ptr<const CompiledGeometry> curve = compile_geometry(circle);
  const auto newton = curve->method("newton");  // an unknown name would be an error value
  if (!newton) {
    std::printf("%s\n", newton.error().message.c_str());
    return 1;
  }
  const std::vector<double> points{2.0, 0.0, 0.0, 0.5};
  ThreadPool pool(2);
  BatchRequest batch(*newton);
  batch.points = points.data();
  batch.count = 2;
  const std::vector<ProjectionResult> results = project_batch(pool, batch);
  print("curve newton", results[0]);
  print("curve newton", results[1]);

  const auto unknown = curve->method("gsa");
  std::printf("%s\n", unknown ? "gsa found" : unknown.error().message.c_str());
  return 0;
}
