#include "solvers/surface/gsa.hpp"

#include <cmath>

namespace footpoint::surface {

namespace {
// §2.2: "k_n could be incremented by a small positive constant ε". The paper gives no value; with
// the cancellation-free form of eqs. (11)-(17) below, any small value gives the tangent-plane
// limit, so this only keeps k_n = 0 from dividing by zero.
constexpr double kNormalCurvaturePerturbation = 1e-12;
}  // namespace

PaperStep gsa_step(const Vec3& p, const SurfaceJet& jet) {
  PaperStep step;
  // eq. (4): n = A / B, A = s_u x s_v
  const Vec3 A = cross(jet.su, jet.sv);
  const double B = norm(A);
  if (!(B > 0.0)) {
    step.failure = std::isnan(B) ? Status::non_finite : Status::degenerate;
    return step;
  }
  const Vec3 n = A / B;
  const Vec3 r = p - jet.s;  // p - p0
  // eq. (6) coefficients
  const double E = dot(jet.su, jet.su), F = dot(jet.su, jet.sv), G = dot(jet.sv, jet.sv);
  const double C1 = dot(jet.su, n), C2 = dot(jet.sv, n);
  const double S1 = dot(r, jet.su), S2 = dot(r, jet.sv), S3 = dot(r, n);
  // eq. (7) (C3 = 1)
  const double D = C1 * C1 * G - 2.0 * C1 * C2 * F + C2 * C2 * E - E * G + F * F;
  if (D == 0.0) {
    step.failure = Status::degenerate;
    return step;
  }
  const double a1 = -(C1 * C2 * S2 - C1 * G * S3 - C2 * C2 * S1 + C2 * F * S3 - F * S2 + G * S1) / D;
  const double a2 = (C1 * C1 * S2 - C1 * C2 * S1 - C1 * F * S3 + C2 * E * S3 - E * S2 + F * S1) / D;
  // eq. (9): |T|^2 = I(T, T). T = 0 means p - p0 is normal: q - p0 is normal too and C4 = C5 = 0.
  const double I = E * a1 * a1 + 2.0 * F * a1 * a2 + G * a2 * a2;
  if (I == 0.0) return step;
  // eq. (10): k_n = II(T, T) / I(T, T), with L, M, N the second fundamental form
  const double L = dot(jet.suu, n), M = dot(jet.suv, n), N = dot(jet.svv, n);
  double kn = (L * a1 * a1 + 2.0 * M * a1 * a2 + N * a2 * a2) / I;
  if (kn == 0.0) kn += kNormalCurvaturePerturbation;  // §2.2
  // eqs. (11)-(17): R = 1/|k_n|, m = p0 + n/k_n, w = 1 - R/|m - p|, q = p + (m - p) w, i.e.
  // q = m + R (p - m)/|p - m|. With Q = |k_n| |p - m| = sqrt(1 - 2 k_n <r,n> + k_n^2 |r|^2) this
  // is, without the cancellation of m far away when k_n is small,
  //   q - p0 = (r + n (k_n |r|^2 - 2 <r,n>) / (Q + 1)) / Q.
  const double rr = dot(r, r);
  const double Q = std::sqrt(1.0 - 2.0 * kn * S3 + kn * kn * rr);
  if (!(Q > 0.0)) {  // p is the centre m of the sphere: every point of it is as near
    step.failure = std::isnan(Q) ? Status::non_finite : Status::degenerate;
    return step;
  }
  const Vec3 q_p0 = (r + n * ((kn * rr - 2.0 * S3) / (Q + 1.0))) / Q;
  // eqs. (19)-(20)
  const double C4 = dot(q_p0, jet.su), C5 = dot(q_p0, jet.sv);
  const double EGF = E * G - F * F;
  if (!(EGF > 0.0)) {
    step.failure = std::isnan(EGF) ? Status::non_finite : Status::degenerate;
    return step;
  }
  step.du = (C4 * G - C5 * F) / EGF;
  step.dv = -(C4 * F - C5 * E) / EGF;
  return step;
}

namespace {
struct Gsa {
  PaperStep step(const Vec3& p, double, double, const SurfaceJet& jet) const { return gsa_step(p, jet); }
};
}  // namespace

ProjectionResult project_gsa(const SurfaceFormulas& formulas, const ParamBox& box, const Vec3& p,
                             const Options& options) {
  Gsa method;
  return run_paper_iteration("gsa", method, formulas, box, p, options);
}

}  // namespace footpoint::surface
