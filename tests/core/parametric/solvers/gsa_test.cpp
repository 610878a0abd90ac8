// gsa_step evaluates [GSA]'s map with the terms that vanish identically left out
// (C1 = <s_u, n> = C2 = <s_v, n> = 0, the normal part of q - p0): it must agree with the formulas
// as printed, eqs. (4)-(20), transcribed here term by term, wherever the step is well conditioned.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "parametric/solvers/gsa.hpp"
#include "surface_fixtures.hpp"

using namespace footpoint;
using namespace footpoint::test;

namespace {

// [GSA]'s increment exactly as printed (k_n = 0 not handled: not drawn here), and
// |k_n| |p - s|: the printed eqs. (14)-(17) lose about -log10 of it in digits.
std::array<double, 3> printed_gsa_step(const Vec3& p, const SurfaceJet& j) {
  const Vec3 A = cross(j.su, j.sv);  // eq. (4)
  const Vec3 n = A / norm(A);
  const double E = dot(j.su, j.su), F = dot(j.su, j.sv), G = dot(j.sv, j.sv);
  const double C1 = dot(j.su, n), C2 = dot(j.sv, n);  // eq. (6), C3 = 1
  const Vec3 r = p - j.s;
  const double S1 = dot(r, j.su), S2 = dot(r, j.sv), S3 = dot(r, n);
  const double D = C1 * C1 * G - 2 * C1 * C2 * F + C2 * C2 * E - E * G + F * F;  // eq. (7)
  const double a1 = -(C1 * C2 * S2 - C1 * G * S3 - C2 * C2 * S1 + C2 * F * S3 - F * S2 + G * S1) / D;
  const double a2 = (C1 * C1 * S2 - C1 * C2 * S1 - C1 * F * S3 + C2 * E * S3 - E * S2 + F * S1) / D;
  const double I = E * a1 * a1 + 2 * F * a1 * a2 + G * a2 * a2;  // eq. (9)
  const double L = dot(j.suu, n), M = dot(j.suv, n), N = dot(j.svv, n);
  const double kn = (L * a1 * a1 + 2 * M * a1 * a2 + N * a2 * a2) / I;                // eq. (10)
  const double R = 1.0 / std::abs(kn);                                                // eq. (11)
  const Vec3 m = j.s + n / kn;                                                        // eq. (12)
  const double w = 1.0 - R / norm(m - p);                                             // eqs. (14)-(16)
  const Vec3 q = p + (m - p) * w;                                                     // eq. (17)
  const double C4 = dot(q - j.s, j.su), C5 = dot(q - j.s, j.sv);                      // eq. (19)
  return {(C4 * G - C5 * F) / (E * G - F * F), -(C4 * F - C5 * E) / (E * G - F * F),  // eq. (20)
          std::abs(kn) * norm(r)};
}

}  // namespace

TEST_CASE("gsa_step is the printed GSA map (eqs. (4)-(20))") {
  const auto s3 =
      make_surface("u^6+u^5*v+v^6-u^2*v^3+u*v^4-v^5+u^4+u^3*v+v^4+u^3-u*v^2+v^3+u*v+v^2+1",
                   "u^6+2*u^4*v^2-v^6+u^5+u^2*v^3+v^5+u^4-u*v^3+u^3-2*u*v^2+v^3+4*u*v+2*v^2+2*u+2*v+1",
                   "u^6+u*v^5+u^4*v+u^2*v^3+u^3*v+2*u^2*v^2+v^4+u^3+2*u*v+u", {0, 2}, {0, 2});
  const auto e1 = make_surface("u+v", "sin(u)+2*cos(v)", "sin(u+v)", {-25, 25}, {-25, 25});
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int compared = 0;
  for (const auto* g : {s3.get(), e1.get()}) {
    const ParamBox& b = g->domain();
    for (int i = 0; i < 200; ++i) {
      const SurfaceJet j =
          g->formulas().jet(b.umin + (b.umax - b.umin) * U(rng), b.vmin + (b.vmax - b.vmin) * U(rng));
      const double scale = 1.0 + norm(j.s);
      const Vec3 p = j.s + Vec3{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5} * scale;
      const surface::PaperStep ours = surface::gsa_step(p, j);
      REQUIRE(ours.failure == Status::converged);
      const std::array<double, 3> printed = printed_gsa_step(p, j);
      // the printed form cancels when the sphere is huge (k_n |p - s| << 1): compare where it
      // keeps at least 10 digits
      if (!(printed[2] > 1e-4)) continue;
      const double tol = 1e-9 * (std::abs(printed[0]) + std::abs(printed[1]));
      INFO("point " << i << ": ours (" << ours.du << ", " << ours.dv << "), printed (" << printed[0] << ", "
                    << printed[1] << ")");
      CHECK(std::abs(ours.du - printed[0]) <= tol);
      CHECK(std::abs(ours.dv - printed[1]) <= tol);
      ++compared;
    }
  }
  CHECK(compared > 200);
}
