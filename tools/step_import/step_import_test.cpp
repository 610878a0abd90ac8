// footpoint-import against closed forms: a sphere, a cylinder and a box made with Open CASCADE,
// written to a STEP file here, imported, each face's definition read as the server reads a posted
// one, compiled, and projected with `auto`; the distances are checked against the shapes' own
// formulas (not against footpoint): | |p - c| - r | for the sphere, | |p_xy - c_xy| - r | for the
// cylinder's side (points level with it), | |(rho - R, z)| - r | for the torus, and the plane's
// distance for the planar faces (points above the face's centre).
#include <doctest/doctest.h>
#include <unistd.h>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRep_Builder.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Compound.hxx>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "compiled/compiled_geometry.hpp"
#include "geometry_json.hpp"
#include "json_reader.hpp"
#include "step_import.hpp"

namespace {

using footpoint::Vec3;

constexpr Vec3 kSphereCentre{1.0, 2.0, 3.0};
constexpr double kSphereRadius = 2.0;
constexpr Vec3 kCylinderBase{6.0, 0.0, -1.0};  // axis +z
constexpr double kCylinderRadius = 1.5, kCylinderHeight = 4.0;
constexpr Vec3 kTorusCentre{0.0, 8.0, 0.5};  // axis +z
constexpr double kTorusMajor = 2.0, kTorusMinor = 0.5;

std::string write_step_file() {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  builder.Add(compound,
              BRepPrimAPI_MakeSphere(gp_Pnt(kSphereCentre.x, kSphereCentre.y, kSphereCentre.z), kSphereRadius)
                  .Shape());
  builder.Add(compound,
              BRepPrimAPI_MakeCylinder(
                  gp_Ax2(gp_Pnt(kCylinderBase.x, kCylinderBase.y, kCylinderBase.z), gp_Dir(0, 0, 1)),
                  kCylinderRadius, kCylinderHeight)
                  .Shape());
  builder.Add(compound, BRepPrimAPI_MakeTorus(
                            gp_Ax2(gp_Pnt(kTorusCentre.x, kTorusCentre.y, kTorusCentre.z), gp_Dir(0, 0, 1)),
                            kTorusMajor, kTorusMinor)
                            .Shape());
  builder.Add(compound, BRepPrimAPI_MakeBox(gp_Pnt(-8, -1, -1), 2.0, 3.0, 4.0).Shape());
  char name[] = "/tmp/footpoint-import-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  close(fd);
  const std::string path = std::string(name) + ".step";
  std::rename(name, path.c_str());
  STEPControl_Writer writer;
  REQUIRE(writer.Transfer(compound, STEPControl_AsIs) == IFSelect_RetDone);
  REQUIRE(writer.Write(path.c_str()) == IFSelect_RetDone);
  return path;
}

std::shared_ptr<const footpoint::CompiledGeometry> compile(const nlohmann::json& definition) {
  const std::string text = definition.dump();
  footpoint::server::JsonReader reader(text);
  return footpoint::compile_geometry(footpoint::server::read_geometry(reader, ""));
}

double auto_distance(const footpoint::CompiledGeometry& g, const Vec3& p) {
  const double x[3] = {p.x, p.y, p.z};
  const auto r = g.method("auto").value().project(x, footpoint::Options{});
  CHECK(r.summary.status == footpoint::Status::converged);
  CHECK(r.summary.certificate.certified);
  return r.distance;
}

}  // namespace

TEST_CASE("footpoint-import: a STEP file's faces projected against closed forms") {
  const std::string path = write_step_file();
  const nlohmann::json imported = footpoint::import::import_step(path);
  std::remove(path.c_str());
  // A sphere's 1 face, a cylinder's 3 (side, two caps), a torus's 1, a box's 6.
  REQUIRE(imported["faces"].size() == 11);
  CHECK(imported["skipped"].empty());
  CHECK(imported["trimmed"] == false);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int spheres = 0, sides = 0, tori = 0, planes = 0;
  for (const auto& face : imported["faces"]) {
    const std::string type = face["surface"];
    const auto& def = face["definition"];
    CAPTURE(type);
    const auto g = compile(def);
    if (type == "Geom_SphericalSurface") {
      ++spheres;
      CHECK(def.contains("weights"));  // rational
      for (int k = 0; k < 20; ++k) {
        const Vec3 p{kSphereCentre.x + 3 * unit(rng), kSphereCentre.y + 3 * unit(rng),
                     kSphereCentre.z + 3 * unit(rng)};
        const Vec3 d = p - kSphereCentre;
        const double expected = std::fabs(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z) - kSphereRadius);
        CHECK(auto_distance(*g, p) == doctest::Approx(expected).epsilon(1e-12));
      }
    } else if (type == "Geom_CylindricalSurface") {
      ++sides;
      for (int k = 0; k < 20; ++k) {
        const Vec3 p{kCylinderBase.x + 2.5 * unit(rng), kCylinderBase.y + 2.5 * unit(rng),
                     kCylinderBase.z + kCylinderHeight * (0.5 + 0.4 * unit(rng))};
        const double expected =
            std::fabs(std::hypot(p.x - kCylinderBase.x, p.y - kCylinderBase.y) - kCylinderRadius);
        CHECK(auto_distance(*g, p) == doctest::Approx(expected).epsilon(1e-12));
      }
    } else if (type == "Geom_ToroidalSurface") {
      ++tori;
      for (int k = 0; k < 20; ++k) {
        const Vec3 p{kTorusCentre.x + 3 * unit(rng), kTorusCentre.y + 3 * unit(rng),
                     kTorusCentre.z + unit(rng)};
        const double rho = std::hypot(p.x - kTorusCentre.x, p.y - kTorusCentre.y);
        const double expected = std::fabs(std::hypot(rho - kTorusMajor, p.z - kTorusCentre.z) - kTorusMinor);
        CHECK(auto_distance(*g, p) == doctest::Approx(expected).epsilon(1e-12));
      }
    } else if (type == "Geom_Plane") {
      ++planes;
      // The plane through three corners of the net; p above the centre of the net.
      const auto& net = def["control_points"];
      const auto corner = [&](std::size_t i, std::size_t j) {
        return Vec3{net[i][j][0].get<double>(), net[i][j][1].get<double>(), net[i][j][2].get<double>()};
      };
      const std::size_t nu = net.size() - 1, nv = net[0].size() - 1;
      const Vec3 a = corner(0, 0), b = corner(nu, 0), c = corner(0, nv), e = corner(nu, nv);
      const Vec3 centre = (a + b + c + e) * 0.25, n = cross(b - a, c - a);
      const Vec3 unit_normal = n * (1.0 / std::sqrt(dot(n, n)));
      for (const double h : {0.3, -0.7, 1.9})
        CHECK(auto_distance(*g, centre + unit_normal * h) == doctest::Approx(std::fabs(h)).epsilon(1e-12));
    }
  }
  CHECK(spheres == 1);
  CHECK(sides == 1);
  CHECK(tori == 1);
  CHECK(planes == 8);
}

TEST_CASE("footpoint-import: a file that is no STEP is refused") {
  char name[] = "/tmp/footpoint-import-XXXXXX";
  const int fd = mkstemp(name);
  REQUIRE(fd >= 0);
  REQUIRE(write(fd, "not a step file\n", 16) == 16);
  close(fd);
  CHECK_THROWS_AS(footpoint::import::import_step(name), std::runtime_error);
  std::remove(name);
  CHECK_THROWS_AS(footpoint::import::import_step("/nonexistent/footpoint.step"), std::runtime_error);
}
