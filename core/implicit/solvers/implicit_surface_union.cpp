#include "implicit/solvers/implicit_surface_union.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "implicit/solvers/implicit_surface_auto.hpp"
#include "implicit/solvers/implicit_surface_certificate.hpp"
#include "solvers/answer_multiplicity.hpp"

namespace footpoint::surface_implicit {

namespace {

// x lies on the piece's surface to the rounding of its residual |g| / |grad g|.
bool on_piece(const SurfacePiece& piece, Vec3 x) {
  const ImplicitSurfaceJet j = piece.equation.jet(x);
  const double g = norm(j.grad);
  return std::fabs(j.f) <= 64.0 * 0x1p-52 * std::max(1.0, norm(x)) * g;
}

}  // namespace

ProjectionResult implicit_surface_union_auto(std::span<const SurfacePiece> pieces, Vec3 p,
                                             const Options& options) {
  if (pieces.size() == 1)
    return implicit_surface_auto(pieces.front().equation, pieces.front().cells, p, options);
  // Each piece answered in full (max_distance applies to the union's answer).
  Options each = options;
  each.max_distance = std::numeric_limits<double>::infinity();
  std::vector<ProjectionResult> answers;
  answers.reserve(pieces.size());
  std::size_t best = pieces.size();
  for (const SurfacePiece& piece : pieces) {
    answers.push_back(implicit_surface_auto(piece.equation, piece.cells, p, each));
    const ProjectionResult& a = answers.back();
    if (std::isfinite(a.distance) && (best == pieces.size() || a.distance < answers[best].distance))
      best = answers.size() - 1;
  }
  if (best == pieces.size()) return answers.front();  // no piece has an answer: degenerate
  ProjectionResult r = answers[best];
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  int starts = 0;
  double lower = r.distance;
  bool computed = true;
  std::vector<ReachedFoot> reached;
  std::vector<Minimum> minima;
  const bool certify = options.certify.value_or(true);
  for (std::size_t i = 0; i < answers.size(); ++i) {
    const ProjectionResult& a = answers[i];
    starts += a.summary.starts;
    if (!std::isfinite(a.distance)) {
      // A piece where no point was found (its cells not excluded, no sample landed): bounded
      // about the answer.
      if (certify)
        lower =
            std::min(lower, certify_surface_answer(pieces[i].equation, pieces[i].cells, p, foot, r.distance)
                                .certificate.lower_bound);
      continue;
    }
    computed = computed && a.summary.certificate.computed;
    if (a.summary.certificate.computed) lower = std::min(lower, a.summary.certificate.lower_bound);
    reached.push_back({{a.foot[0], a.foot[1], a.foot[2]}, a.distance});
    for (const auto& f : a.summary.multiplicity.feet)
      reached.push_back({{f[0], f[1], f[2]}, norm(p - Vec3{f[0], f[1], f[2]})});
    if (i != best) minima.insert(minima.end(), a.minima.begin(), a.minima.end());
    // A foot on another piece too: where two factor surfaces meet, grad f = 0.
    if (i != best && on_piece(pieces[i], foot)) {
      r.summary.location = Location::singular_point;
      r.summary.orthogonality[0] = 0.0;
    }
  }
  r.summary.starts = starts;
  if (computed) {
    Certificate& c = r.summary.certificate;
    c.lower_bound = lower;
    c.certified = Certificate::meets_gap(r.distance, lower, c.absolute_gap);
    c.boxes = 0;
    for (const ProjectionResult& a : answers) c.boxes += a.summary.certificate.boxes;
    if (!c.certified && c.reason == CertificateReason::gap_met)
      c.reason = CertificateReason::budget_exhausted;
  }
  if (r.summary.multiplicity.kind != Multiplicity::continuum)
    r.summary.multiplicity = tied_feet(r, p, reached);
  if (options.all_minima) {
    // The answer's list first, then the other pieces' minima, nearest first, each foot once.
    std::stable_sort(minima.begin(), minima.end(),
                     [](const Minimum& a, const Minimum& b) { return a.distance < b.distance; });
    for (const Minimum& m : minima) {
      bool seen = false;
      for (const Minimum& k : r.minima)
        seen = seen || norm(Vec3{m.foot[0], m.foot[1], m.foot[2]} - Vec3{k.foot[0], k.foot[1], k.foot[2]}) <=
                           kDistinctFoot * (1.0 + norm(Vec3{m.foot[0], m.foot[1], m.foot[2]}));
      if (!seen && m.distance <= options.max_distance) r.minima.push_back(m);
    }
    if (!r.minima.empty())
      std::stable_sort(r.minima.begin() + 1, r.minima.end(),
                       [](const Minimum& a, const Minimum& b) { return a.distance < b.distance; });
    const bool truncated = std::any_of(answers.begin(), answers.end(),
                                       [](const ProjectionResult& a) { return a.minima_truncated; });
    r.minima_truncated = false;
    cap_minima(r, options);
    r.minima_truncated = r.minima_truncated || truncated;
  }
  if (r.summary.status != Status::beyond_max_distance && r.distance > options.max_distance) {
    r.summary.status = Status::beyond_max_distance;
    withhold_answer(r);
  }
  return r;
}

Certificate certify_union_answer(std::span<const SurfacePiece> pieces, Vec3 p, Vec3 foot, double distance) {
  Certificate c;
  for (const SurfacePiece& piece : pieces) {
    const Certificate one =
        certify_surface_answer(piece.equation, piece.cells, p, foot, distance).certificate;
    if (!c.computed) {
      c = one;
      continue;
    }
    c.boxes += one.boxes;
    if (one.lower_bound < c.lower_bound) {
      c.lower_bound = one.lower_bound;
      c.reason = one.reason;
    }
  }
  c.certified = c.computed && Certificate::meets_gap(distance, c.lower_bound, c.absolute_gap);
  if (c.computed && !c.certified && c.reason == CertificateReason::gap_met)
    c.reason = CertificateReason::budget_exhausted;
  return c;
}

}  // namespace footpoint::surface_implicit
