#include "parametric/solvers/gsa.hpp"

#include <cmath>

namespace footpoint::surface {

namespace {
// [GSA] §2.2: "k_n could be incremented by a small positive constant ε". The paper gives no value; with
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
  // eq. (6) coefficients. C1 = <s_u, n> and C2 = <s_v, n> vanish identically (n is normal to
  // s_u and s_v) and C3 = 1, so eq. (7) reduces to the tangent-plane solve
  //   α1 = (G S1 - F S2) / (EG - F^2),  α2 = (E S2 - F S1) / (EG - F^2)
  // (the printed formulas with C1 = C2 = 0; computing the zeros adds only rounding).
  const double E = dot(jet.su, jet.su), F = dot(jet.su, jet.sv), G = dot(jet.sv, jet.sv);
  const double S1 = dot(r, jet.su), S2 = dot(r, jet.sv), S3 = dot(r, n);
  const double EGF = E * G - F * F;
  if (!(EGF > 0.0)) {
    step.failure = std::isnan(EGF) ? Status::non_finite : Status::degenerate;
    return step;
  }
  const double a1 = (G * S1 - F * S2) / EGF;
  const double a2 = (E * S2 - F * S1) / EGF;
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
  //   q - p0 = (r + n (k_n |r|^2 - 2 <r,n>) / (Q + 1)) / Q,
  // of which eqs. (19)-(20) below need only Q (the n part is orthogonal to s_u and s_v).
  const double Q = std::sqrt(1.0 - 2.0 * kn * S3 + kn * kn * dot(r, r));
  if (!(Q > 0.0)) {  // p is the centre m of the sphere: every point of it is as near
    step.failure = std::isnan(Q) ? Status::non_finite : Status::degenerate;
    return step;
  }
  // eqs. (19)-(20): C4 = <q - p0, s_u> = S1 / Q and C5 = <q - p0, s_v> = S2 / Q, so
  // (Δu, Δv) = (C4 G - C5 F, C5 E - C4 F) / (EG - F^2) = (α1, α2) / Q: the tangent-plane step
  // scaled by the curvature sphere.
  step.du = a1 / Q;
  step.dv = a2 / Q;
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
