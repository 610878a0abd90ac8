#include "compiled/bspline_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "geometry/compile_budget.hpp"
#include "parametric/geometry/nurbs_patches.hpp"
#include "parametric/solvers/surface_result.hpp"
#include "solvers/piecewise_nearest.hpp"

namespace footpoint {

namespace {

// The cells of one Bézier piece: a piece is a polynomial of low degree over one knot span, far
// smoother than the formulas the defaults are set for (parametric/seeding/surface_cells.hpp). The
// certificates' kept sub-boxes are shared out: a formula surface's 4096 pairs over all the pieces.
SurfaceSeedingOptions piece_seeding(std::size_t pieces) {
  SurfaceSeedingOptions o;
  o.min_cells = 16;
  o.target_cells = 256;
  o.max_bytes = std::size_t{256} << 10;
  o.refinement_pairs_per_cell = 0;
  o.min_refinement_pairs = std::max<std::size_t>(SurfaceSeedingOptions{}.min_refinement_pairs / pieces, 16);
  return o;
}

// The distinct knots within [lo, hi], both ends included.
std::vector<double> breaks_of(const std::vector<double>& knots, double lo, double hi) {
  std::vector<double> out;
  for (const double k : knots)
    if (k >= lo && k <= hi && (out.empty() || k > out.back())) out.push_back(k);
  return out;
}

// The index b of the span [breaks[b], breaks[b + 1]] holding x (the last one at the upper end).
std::size_t span_of(const std::vector<double>& breaks, double x) {
  const auto it = std::upper_bound(breaks.begin(), breaks.end(), x);
  const auto b = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - breaks.begin() - 1, 0));
  return std::min(b, breaks.size() - 2);
}

Vec3 euclidean(const std::array<double, 4>& h) { return {h[0] / h[3], h[1] / h[3], h[2] / h[3]}; }

// Two Bézier control points equal to the rounding of the blossom (nurbs_patches.hpp).
bool same_point(const std::array<double, 4>& a, const std::array<double, 4>& b, double magnitude) {
  return norm(euclidean(a) - euclidean(b)) <= 0x1p-40 * magnitude;
}

double magnitude_of(const std::vector<std::array<double, 4>>& weighted) {
  double m = 0.0;
  for (const auto& h : weighted) {
    const Vec3 x = euclidean(h);
    m = std::max({m, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  }
  return m;
}

// Unit vectors differ by more than the rounding of two evaluations: a kink between two pieces.
bool directions_differ(Vec3 a, Vec3 b) {
  const double la = norm(a), lb = norm(b);
  if (!(la > 0.0) || !(lb > 0.0)) return false;
  return norm(a / la - b / lb) > 1e-8;
}

GeometryDefinition piece_definition(
    GeometryType type, const std::vector<std::pair<std::string, std::array<double, 2>>>& domain) {
  GeometryDefinition def;
  def.type = type;
  def.domain = domain;
  return def;
}

// The global parameter of the local s in [0, 1] on [a, b]: the ends exactly.
double global_of(double s, double a, double b) { return s <= 0.0 ? a : s >= 1.0 ? b : a + (b - a) * s; }

// A piece's Bézier patch (its formula's points, as nurbs_patches has them: the homogeneous
// points w x, w y, w z and the weights w, left out where every weight is 1), for nearest_on_patch;
// none for a degree above BezierPatch::kMaxDegree.
std::optional<BezierPatch> bezier_patch(const nurbs::SurfacePiece& piece, const nurbs::Surface& surface) {
  const auto [p, q] = surface.degree;
  if (p > BezierPatch::kMaxDegree || q > BezierPatch::kMaxDegree) return std::nullopt;
  std::vector<Vec3> net;
  std::vector<double> weights;
  bool rational = false;
  for (const auto& h : piece.bezier) {
    net.push_back({h[0], h[1], h[2]});
    weights.push_back(h[3]);
    rational = rational || h[3] != 1.0;
  }
  if (!rational) weights.clear();
  return BezierPatch(p, q, std::move(net), std::move(weights));
}

// The sub-patches nearest_on_patch may bound for one point before the piece's `auto` is asked: a
// rational piece's distance is convex in its parameters only away from a pole (the sphere's pieces
// meet one), where the polynomial pieces' is on the whole piece or its first quarters.
constexpr int kPatchBoxes = 24, kRationalPatchBoxes = 48;

// The pieces' certified `auto` answers combined (solvers/piecewise_nearest.hpp). `to_local(k, t,
// s)` maps options.initial's global parameters to piece k's local ones (false: not on piece k);
// `finish(k, r)` locates piece k's answer on the whole geometry and maps its parameters back.
// `direct(k, o, cutoff)` may answer piece k without its `auto` (an empty optional: it does not).
template <class Pieces, class ToLocal, class Finish, class Direct>
ProjectionResult nearest_piece(const Pieces& pieces, const PieceTree& tree, const Vec3& p,
                               const Options& options, ToLocal to_local, Finish finish, Direct direct) {
  return nearest_over_pieces(tree, p, options,
                             [&](std::size_t k, const Options& o, double cutoff) {
                               std::optional<ProjectionResult> answer = direct(k, o, cutoff);
                               if (!answer) {
                                 Options piece_options = o;
                                 std::array<double, 3> local{};
                                 if (o.initial && to_local(k, *o.initial, local))
                                   piece_options.initial = local;
                                 else
                                   piece_options.initial.reset();
                                 const double point[3] = {p.x, p.y, p.z};
                                 answer = pieces[k]->project(point, "auto", piece_options).value();
                               }
                               ProjectionResult& r = *answer;
                               // The normal is the whole geometry's (foot_normal), not the piece's: none on a
                               // kink.
                               r.normal.fill(std::numeric_limits<double>::quiet_NaN());
                               r.signed_distance = std::numeric_limits<double>::quiet_NaN();
                               finish(k, r);
                               return std::move(r);
                             })
      .result;
}

constexpr std::uint32_t kAutoStatuses =
    statuses({Status::converged, Status::max_iterations, Status::non_finite, Status::degenerate,
              Status::beyond_max_distance, Status::deadline_exceeded});

constexpr MethodInfo kSurfaceAuto{
    "auto",
    "global nearest point over the closed domain: a branch and bound over the Bézier pieces (the boxes of "
    "their control points), each piece by the parametric surfaces' certified auto; options.initial is a "
    "warm start",
    "",
    {},
    kGlobalOptions | option_initial | option_max_minima,
    kAutoStatuses};
constexpr MethodInfo kCurveAuto{
    "auto",
    "global nearest point over the closed domain: a branch and bound over the Bézier pieces (the boxes of "
    "their control points), each piece by the parametric curves' certified auto",
    "",
    {},
    kGlobalOptions | option_max_minima,
    kAutoStatuses};

// auto, then the pieces' local methods (the papers'), which run from piece to piece.
std::vector<MethodInfo> with_local_methods(const MethodInfo& auto_info,
                                           const std::vector<MethodInfo>& pieces) {
  std::vector<MethodInfo> out{auto_info};
  for (const MethodInfo& m : pieces)
    if (m.name != "auto") out.push_back(m);
  return out;
}

// x moved by whole periods hi - lo into [lo, hi] (a closed direction's parameter; finite x only).
double into_period(double x, double lo, double hi) {
  if (!std::isfinite(x) || (x >= lo && x <= hi)) return x;
  const double period = hi - lo;
  return std::clamp(x - period * std::floor((x - lo) / period), lo, hi);
}

// The global parameters of piece-local ones, continued beyond [0, 1] (the ends exactly).
template <std::size_t N>
std::array<double, 2> to_global(const std::array<std::array<double, 2>, N>& span,
                                const std::array<double, 2>& s) {
  std::array<double, 2> out{};
  for (std::size_t d = 0; d < N; ++d)
    out[d] = s[d] == 0.0   ? span[d][0]
             : s[d] == 1.0 ? span[d][1]
                           : span[d][0] + (span[d][1] - span[d][0]) * s[d];
  return out;
}
template <std::size_t N>
std::array<double, 3> to_local(const std::array<std::array<double, 2>, N>& span,
                               const std::array<double, 2>& t) {
  std::array<double, 3> out{};
  for (std::size_t d = 0; d < N; ++d) out[d] = (t[d] - span[d][0]) / (span[d][1] - span[d][0]);
  return out;
}

// A local method run from piece to piece (bspline_geometry.hpp): `spans[k]` is piece k's span per
// parameter, `piece_of(t)` the piece holding the global parameters t (moved into the domain by a
// period along a closed direction), or -1 outside the domain.
// Without a start, the method starts on `first` from its own default start.
template <std::size_t N, class Pieces, class PieceOf>
ProjectionResult follow_pieces(std::string_view name, const Pieces& pieces,
                               const std::vector<std::array<std::array<double, 2>, N>>& spans,
                               PieceOf piece_of, const Vec3& p, const Options& options,
                               std::optional<std::array<double, 2>> start, std::size_t first) {
  const double point[3] = {p.x, p.y, p.z};
  std::ptrdiff_t k = start ? piece_of(*start) : static_cast<std::ptrdiff_t>(first);
  if (k < 0) k = static_cast<std::ptrdiff_t>(first);
  std::optional<std::array<double, 3>> local;
  if (start) local = to_local<N>(spans[static_cast<std::size_t>(k)], *start);
  ProjectionResult r;
  int iterations = 0;
  std::vector<std::array<double, 3>> trace;
  for (std::size_t hop = 0; hop <= pieces.size(); ++hop) {
    const auto& span = spans[static_cast<std::size_t>(k)];
    Options o = options;
    o.certify = false;
    o.initial = local;  // the piece's own default start when there is none
    r = pieces[static_cast<std::size_t>(k)]->project(point, name, o).value();
    iterations += r.summary.iterations;
    for (auto step : r.trace) {
      for (std::size_t d = 0; d < N; ++d) step[d] *= span[d][1] - span[d][0];
      trace.push_back(step);
    }
    r.params = to_global<N>(span, r.params);
    if (r.summary.status != Status::outside_domain) break;
    std::array<double, 2> restart = r.params;
    const std::ptrdiff_t next = piece_of(restart);
    if (next < 0 || next == k) break;  // beyond the whole domain
    k = next;
    local = to_local<N>(spans[static_cast<std::size_t>(k)], restart);
  }
  r.summary.iterations = iterations;
  r.trace = std::move(trace);
  if (r.summary.location == Location::edge || r.summary.location == Location::corner ||
      r.summary.location == Location::endpoint)
    r.summary.location = Location::interior;  // a piece's edge inside the domain
  r.summary.on_boundary = false;
  r.normal.fill(std::numeric_limits<double>::quiet_NaN());
  r.signed_distance = std::numeric_limits<double>::quiet_NaN();
  return r;
}

// With options.certify, a local answer gets `auto`'s certificate of the whole geometry.
template <class Geometry>
void certify_local(const Geometry& g, const Vec3& p, const Options& options, ProjectionResult& r) {
  if (!options.certify.value_or(false) || !std::isfinite(r.distance)) return;
  Options o;
  o.certify = true;
  const ProjectionResult global = g.project_auto(p, o);
  Certificate c = global.summary.certificate;
  if (!c.computed) return;
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  c.absolute_gap = Certificate::absolute_gap_at(p, foot);
  c.lower_bound = std::fmin(c.lower_bound, r.distance);
  c.certified = Certificate::meets_gap(r.distance, c.lower_bound, c.absolute_gap);
  if (c.certified)
    c.reason = CertificateReason::gap_met;
  else if (std::isfinite(global.distance) &&
           global.distance < r.distance - std::fmax(Certificate::kRelativeGap * r.distance, c.absolute_gap))
    c.reason = CertificateReason::nearer_point;
  r.summary.certificate = c;
}

GeometryError bspline_error(const nurbs::DefinitionError& e) {
  return GeometryError("bad_bspline", e.field, -1, e.field + " " + e.message);
}

std::vector<nurbs::SurfacePiece> surface_pieces(const nurbs::Surface& s, std::size_t max_nodes) {
  try {
    return nurbs::bezier_pieces(s, max_nodes);
  } catch (const formula::FormulaError& e) {
    throw GeometryError(formula::to_string(e.kind), "control_points", -1, e.what());
  }
}
std::vector<nurbs::CurvePiece> curve_pieces(const nurbs::Curve& c, std::size_t max_nodes) {
  try {
    return nurbs::bezier_pieces(c, max_nodes);
  } catch (const formula::FormulaError& e) {
    throw GeometryError(formula::to_string(e.kind), "control_points", -1, e.what());
  }
}

}  // namespace

// ---- surfaces ------------------------------------------------------------------------------------

BSplineSurface::BSplineSurface(GeometryDefinition def, nurbs::Surface surface,
                               const formula::CompileLimits& limits, CompileBudget& budget)
    : CompiledGeometry(std::move(def)), surface_(std::move(surface)) {
  breaks_u_ = breaks_of(surface_.knots_u, surface_.umin(), surface_.umax());
  breaks_v_ = breaks_of(surface_.knots_v, surface_.vmin(), surface_.vmax());
  std::vector<nurbs::SurfacePiece> pieces = surface_pieces(surface_, limits.max_nodes);
  const SurfaceSeedingOptions seeding = piece_seeding(pieces.size());
  std::vector<Box3> hulls;
  for (nurbs::SurfacePiece& piece : pieces) {
    pieces_.push_back(std::make_unique<ParametricSurface>(
        piece_definition(GeometryType::parametric_surface, {{"u", {0.0, 1.0}}, {"v", {0.0, 1.0}}}),
        std::move(piece.program), ParamBox{0.0, 1.0, 0.0, 1.0}, budget, seeding));
    spans_.push_back(piece.span);
    hulls.push_back(piece.hull);
    patches_.push_back(bezier_patch(piece, surface_));
    budget.check();
  }
  tree_ = PieceTree(std::move(hulls));
  methods_ = bspline_surface_methods();
  // Closed directions: the first and last pieces' boundary rows (columns) of Bézier points agree.
  const std::size_t nu = breaks_u_.size() - 1, nv = breaks_v_.size() - 1;
  const int p = surface_.degree[0], q = surface_.degree[1];
  const double magnitude = magnitude_of(surface_.weighted);
  auto net = [&](std::size_t a, std::size_t b, int k, int l) -> const std::array<double, 4>& {
    return pieces[a * nv + b].bezier[static_cast<std::size_t>(k * (q + 1) + l)];
  };
  closed_[0] = closed_[1] = true;
  for (std::size_t b = 0; b < nv; ++b)
    for (int l = 0; l <= q; ++l)
      closed_[0] = closed_[0] && same_point(net(0, b, 0, l), net(nu - 1, b, p, l), magnitude);
  for (std::size_t a = 0; a < nu; ++a)
    for (int k = 0; k <= p; ++k)
      closed_[1] = closed_[1] && same_point(net(a, 0, k, 0), net(a, nv - 1, k, q), magnitude);
}

const std::vector<MethodInfo>& BSplineSurface::methods() const { return methods_; }
const std::vector<MethodInfo>& bspline_surface_methods() {
  static const std::vector<MethodInfo> m = with_local_methods(kSurfaceAuto, parametric_surface_methods());
  return m;
}

ProjectionResult BSplineSurface::project_with(std::size_t index, const double* p,
                                              const Options& options) const {
  const Vec3 x{p[0], p[1], p[2]};
  return index == 0 ? project_auto(x, options) : project_local(methods_[index].name, x, options);
}

ProjectionResult BSplineSurface::project_local(std::string_view name, const Vec3& p,
                                               const Options& options) const {
  std::vector<std::array<std::array<double, 2>, 2>> spans;
  for (const ParamBox& b : spans_) spans.push_back({{{b.umin, b.umax}, {b.vmin, b.vmax}}});
  const std::size_t nv = breaks_v_.size() - 1;
  const auto piece_of = [&](const std::array<double, 2>& t) -> std::ptrdiff_t {
    if (!(t[0] >= surface_.umin() && t[0] <= surface_.umax() && t[1] >= surface_.vmin() &&
          t[1] <= surface_.vmax()))
      return -1;
    return static_cast<std::ptrdiff_t>(span_of(breaks_u_, t[0]) * nv + span_of(breaks_v_, t[1]));
  };
  // From options.initial, else the domain's centre (as on a formula surface).
  const std::array<double, 2> start =
      options.initial ? std::array<double, 2>{(*options.initial)[0], (*options.initial)[1]}
                      : std::array<double, 2>{0.5 * (surface_.umin() + surface_.umax()),
                                              0.5 * (surface_.vmin() + surface_.vmax())};
  ProjectionResult r = follow_pieces<2>(name, pieces_, spans, piece_of, p, options, start, 0);
  certify_local(*this, p, options, r);
  return r;
}

SurfaceJet BSplineSurface::piece_jet(std::size_t k, double s, double t) const {
  return patches_[k] ? patches_[k]->power_jet(s, t) : pieces_[k]->formulas().jet(s, t);
}

std::size_t BSplineSurface::memory_bytes() const {
  std::size_t bytes =
      sizeof(*this) + surface_.weighted.capacity() * sizeof(surface_.weighted[0]) + tree_.memory_bytes();
  for (const auto& piece : pieces_) bytes += piece->memory_bytes();
  for (const auto& patch : patches_)
    if (patch) bytes += patch->memory_bytes();
  return bytes;
}

bool BSplineSurface::evaluate(const double* t, Evaluation& out) const {
  const double u = t[0], v = t[1];
  const bool inside =
      u >= surface_.umin() && u <= surface_.umax() && v >= surface_.vmin() && v <= surface_.vmax();
  // Inside, the NURBS by de Boor; beyond the domain, the end pieces' polynomials continued.
  SurfaceJet j;
  if (inside) {
    j = nurbs::evaluate(surface_, u, v);
  } else {
    const std::size_t k = span_of(breaks_u_, u) * (breaks_v_.size() - 1) + span_of(breaks_v_, v);
    const ParamBox& b = spans_[k];
    const double hu = 1.0 / (b.umax - b.umin), hv = 1.0 / (b.vmax - b.vmin);
    j = pieces_[k]->formulas().jet((u - b.umin) * hu, (v - b.vmin) * hv);
    j.su = j.su * hu;
    j.sv = j.sv * hv;
    j.suu = j.suu * (hu * hu);
    j.suv = j.suv * (hu * hv);
    j.svv = j.svv * (hv * hv);
  }
  out = evaluation_of(j);
  out.inside_domain = inside;
  return true;
}

bool BSplineSurface::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  if (r.summary.location == Location::pole || r.summary.location == Location::kink) return false;
  // The piece's tangents: its local parameters are the global ones scaled by positive factors, so
  // s_s x s_t has the direction of s_u x s_v.
  const std::size_t k =
      span_of(breaks_u_, r.params[0]) * (breaks_v_.size() - 1) + span_of(breaks_v_, r.params[1]);
  const ParamBox& b = spans_[k];
  const SurfaceJet j =
      piece_jet(k, (r.params[0] - b.umin) / (b.umax - b.umin), (r.params[1] - b.vmin) / (b.vmax - b.vmin));
  const Evaluation e = evaluation_of(j);
  if (!e.normal_defined) return false;
  n = {e.normal.x, e.normal.y, e.normal.z};
  return true;
}

Location BSplineSurface::locate(std::size_t k, Location piece_location, double s, double t) const {
  if (piece_location != Location::edge && piece_location != Location::corner) return piece_location;
  const std::size_t nu = breaks_u_.size() - 1, nv = breaks_v_.size() - 1, a = k / nv, b = k % nv;
  // The piece's edges s = 0, 1 (t = 0, 1): the domain's edges where they are the first or last
  // span's and the direction is not closed; else a knot line inside.
  const bool s_end = s <= 0.0 || s >= 1.0, t_end = t <= 0.0 || t >= 1.0;
  const bool on_u = s_end && !closed_[0] && ((s <= 0.0 && a == 0) || (s >= 1.0 && a == nu - 1));
  const bool on_v = t_end && !closed_[1] && ((t <= 0.0 && b == 0) || (t >= 1.0 && b == nv - 1));
  if (on_u && on_v) return Location::corner;
  if (on_u || on_v) return Location::edge;
  // On a knot line inside: a kink where the normals of the pieces on its two sides differ.
  auto normal = [&](std::size_t piece, double ps, double pt) {
    const SurfaceJet j = piece_jet(piece, ps, pt);
    return cross(j.su, j.sv);
  };
  const Vec3 here = normal(k, s, t);
  if (s_end && !on_u) {
    const std::size_t other = s <= 0.0 ? (a == 0 ? nu - 1 : a - 1) : (a == nu - 1 ? 0 : a + 1);
    if (directions_differ(here, normal(other * nv + b, s <= 0.0 ? 1.0 : 0.0, t))) return Location::kink;
  }
  if (t_end && !on_v) {
    const std::size_t other = t <= 0.0 ? (b == 0 ? nv - 1 : b - 1) : (b == nv - 1 ? 0 : b + 1);
    if (directions_differ(here, normal(a * nv + other, s, t <= 0.0 ? 1.0 : 0.0))) return Location::kink;
  }
  return Location::interior;
}

void BSplineSurface::at_pole(std::size_t k, const Vec3& p, ProjectionResult& r) const {
  const ParametricSurface& piece = *pieces_[k];
  const Vec3 foot{r.foot[0], r.foot[1], r.foot[2]};
  for (const BoxEdge edge : {BoxEdge::umin, BoxEdge::umax, BoxEdge::vmin, BoxEdge::vmax}) {
    const SurfacePole& pole = piece.closure().poles[static_cast<std::size_t>(edge)];
    if (!pole.collapsed ||
        !(norm(foot - pole.point) <= std::fmax(piece.closure().tolerance, 1e-12 * (1.0 + norm(foot)))))
      continue;
    // The foot is the pole: every parameter along the edge gives it. One foot, unless the distance
    // is also flat across the edge (f = ½|s - p|² with f_nn = |s_n|² + <s - p, s_nn> = 0 along the
    // parameter n leaving the edge: p at a centre of curvature, a true continuum).
    const bool along_u = edge == BoxEdge::vmin || edge == BoxEdge::vmax;
    const double s_edge = edge == BoxEdge::umin || edge == BoxEdge::vmin ? 0.0 : 1.0;
    const SurfaceJet j =
        along_u ? piece.formulas().jet(r.params[0], s_edge) : piece.formulas().jet(s_edge, r.params[1]);
    const Vec3 sn = along_u ? j.sv : j.su, snn = along_u ? j.svv : j.suu;
    const double fnn = dot(sn, sn) + dot(j.s - p, snn);
    r.summary.location = Location::pole;
    r.summary.on_boundary = false;
    (along_u ? r.params[1] : r.params[0]) = s_edge;
    if (r.summary.multiplicity.kind == Multiplicity::continuum && fnn > 1e-9 * dot(sn, sn)) {
      r.summary.multiplicity.kind = Multiplicity::unique;
      r.summary.multiplicity.count = 1;
      r.summary.multiplicity.feet.clear();
    }
    return;
  }
}

ProjectionResult BSplineSurface::project_auto(const Vec3& p, const Options& options) const {
  const auto to_local = [&](std::size_t k, const std::array<double, 3>& t, std::array<double, 3>& local) {
    const ParamBox& b = spans_[k];
    if (!b.contains(t[0], t[1])) return false;
    local = {(t[0] - b.umin) / (b.umax - b.umin), (t[1] - b.vmin) / (b.vmax - b.vmin), 0.0};
    return true;
  };
  const auto finish = [&](std::size_t k, ProjectionResult& r) {
    const ParamBox& b = spans_[k];
    if (std::isfinite(r.distance)) at_pole(k, p, r);
    auto map = [&](std::array<double, 2>& t) {
      t = {global_of(t[0], b.umin, b.umax), global_of(t[1], b.vmin, b.vmax)};
    };
    if (std::isfinite(r.distance)) {
      r.summary.location = locate(k, r.summary.location, r.params[0], r.params[1]);
      r.summary.on_boundary = r.summary.location == Location::edge || r.summary.location == Location::corner;
      map(r.params);
    }
    for (Minimum& m : r.minima) {
      m.location = locate(k, m.location, m.params[0], m.params[1]);
      map(m.params);
      for (auto& c : m.copies) map(c);
    }
    for (auto& step : r.trace) {
      step[0] *= b.umax - b.umin;
      step[1] *= b.vmax - b.vmin;
    }
  };
  const auto direct = [&](std::size_t k, const Options& o, double cutoff) -> std::optional<ProjectionResult> {
    // The patch's own branch and bound, where it applies: a polynomial piece, the default
    // options of a certified answer.
    if (!patches_[k] || o.all_minima || o.trace || o.tolerance != 0.0 || o.max_iterations != 0 ||
        (o.certify && !*o.certify))
      return std::nullopt;
    const PatchNearest n = nearest_on_patch(
        *patches_[k], p, patches_[k]->rational() ? kRationalPatchBoxes : kPatchBoxes, cutoff);
    if (!n.proved || n.distance > o.max_distance) return std::nullopt;
    ProjectionResult r = surface::surface_result("auto", p, n.s, n.t, n.jet.s, n.jet.su, n.jet.sv,
                                                 ParamBox{0.0, 1.0, 0.0, 1.0}, &pieces_[k]->closure());
    Summary& summary = r.summary;
    summary.status = Status::converged;
    summary.iterations = n.iterations;
    summary.starts = n.starts;
    summary.step_norm = n.step_norm;
    Certificate& c = summary.certificate;
    c.computed = true;
    c.lower_bound = n.lower_bound;
    c.absolute_gap = Certificate::absolute_gap_at(p, n.jet.s);
    c.certified = Certificate::meets_gap(n.distance, c.lower_bound, c.absolute_gap);
    c.reason = c.certified ? CertificateReason::gap_met : CertificateReason::budget_exhausted;
    c.boxes = n.boxes;
    summary.multiplicity.computed = true;
    // At a pole the parameters along its edge are a continuum; at_pole (finish) makes it one foot
    // where the distance grows across the edge, as for the engine's answers.
    summary.multiplicity.kind = n.pole ? Multiplicity::continuum : Multiplicity::unique;
    summary.multiplicity.count = 1;
    return r;
  };
  return nearest_piece(pieces_, tree_, p, options, to_local, finish, direct);
}

// ---- curves --------------------------------------------------------------------------------------

BSplineCurve::BSplineCurve(GeometryDefinition def, nurbs::Curve curve, const formula::CompileLimits& limits,
                           CompileBudget& budget)
    : CompiledGeometry(std::move(def)), curve_(std::move(curve)) {
  breaks_ = breaks_of(curve_.knots, curve_.tmin(), curve_.tmax());
  std::vector<nurbs::CurvePiece> pieces = curve_pieces(curve_, limits.max_nodes);
  std::vector<Box3> hulls;
  for (nurbs::CurvePiece& piece : pieces) {
    pieces_.push_back(std::make_unique<ParametricCurve>(
        piece_definition(GeometryType::parametric_curve, {{"t", {0.0, 1.0}}}),
        CurveFormulas(std::move(piece.program)), ParamInterval{0.0, 1.0}, budget));
    spans_.push_back(piece.span);
    hulls.push_back(piece.hull);
    budget.check();
  }
  tree_ = PieceTree(std::move(hulls));
  closed_ =
      same_point(pieces.front().bezier.front(), pieces.back().bezier.back(), magnitude_of(curve_.weighted));
  methods_ = with_local_methods(kCurveAuto, pieces_.front()->methods());
}

const std::vector<MethodInfo>& BSplineCurve::methods() const { return methods_; }
const std::vector<MethodInfo>& bspline_curve_methods() {
  static const std::vector<MethodInfo> m = with_local_methods(kCurveAuto, parametric_curve_methods());
  return m;
}

ProjectionResult BSplineCurve::project_with(std::size_t index, const double* p,
                                            const Options& options) const {
  const Vec3 x{p[0], p[1], curve_.dimension == 3 ? p[2] : 0.0};
  return index == 0 ? project_auto(x, options) : project_local(methods_[index].name, x, options);
}

ProjectionResult BSplineCurve::project_local(std::string_view name, const Vec3& p,
                                             const Options& options) const {
  std::vector<std::array<std::array<double, 2>, 1>> spans;
  for (const ParamInterval& b : spans_) spans.push_back({{{b.tmin, b.tmax}}});
  const auto piece_of = [&](std::array<double, 2>& t) -> std::ptrdiff_t {
    if (closed_) t[0] = into_period(t[0], curve_.tmin(), curve_.tmax());
    if (!(t[0] >= curve_.tmin() && t[0] <= curve_.tmax())) return -1;
    return static_cast<std::ptrdiff_t>(span_of(breaks_, t[0]));
  };
  // From options.initial, else from the nearest sample of the piece whose box is nearest (a formula
  // curve's methods start from its nearest sample).
  std::optional<std::array<double, 2>> start;
  if (options.initial) start = std::array<double, 2>{(*options.initial)[0], 0.0};
  std::size_t nearest = 0;
  for (std::size_t k = 1; k < tree_.size(); ++k)
    if (distance_lower_bound(tree_.hull(k), p) < distance_lower_bound(tree_.hull(nearest), p)) nearest = k;
  ProjectionResult r = follow_pieces<1>(name, pieces_, spans, piece_of, p, options, start, nearest);
  certify_local(*this, p, options, r);
  return r;
}

std::size_t BSplineCurve::memory_bytes() const {
  std::size_t bytes =
      sizeof(*this) + curve_.weighted.capacity() * sizeof(curve_.weighted[0]) + tree_.memory_bytes();
  for (const auto& piece : pieces_) bytes += piece->memory_bytes();
  return bytes;
}

bool BSplineCurve::evaluate(const double* t, Evaluation& out) const {
  const bool inside = t[0] >= curve_.tmin() && t[0] <= curve_.tmax();
  CurveJet j;
  if (inside) {
    j = nurbs::evaluate(curve_, t[0]);
  } else {
    const std::size_t k = span_of(breaks_, t[0]);
    const double h = 1.0 / (spans_[k].tmax - spans_[k].tmin);
    j = pieces_[k]->formulas().jet((t[0] - spans_[k].tmin) * h);
    j.d1 = j.d1 * h;
    j.d2 = j.d2 * (h * h);
  }
  out = evaluation_of(j);
  out.inside_domain = inside;
  return true;
}

bool BSplineCurve::foot_normal(const ProjectionResult& r, std::array<double, 3>& n) const {
  return curve_.dimension == 2 && r.summary.location != Location::kink &&
         planar_curve_normal(nurbs::evaluate(curve_, r.params[0]).d1, n);
}

Location BSplineCurve::locate(std::size_t k, Location piece_location, double s) const {
  if (piece_location != Location::endpoint) return piece_location;
  const std::size_t n = pieces_.size();
  if (!closed_ && ((s <= 0.0 && k == 0) || (s >= 1.0 && k == n - 1))) return Location::endpoint;
  // A joint inside (or the seam of a closed curve): a kink where the tangents differ.
  const std::size_t other = s <= 0.0 ? (k == 0 ? n - 1 : k - 1) : (k == n - 1 ? 0 : k + 1);
  if (directions_differ(pieces_[k]->formulas().jet(s).d1,
                        pieces_[other]->formulas().jet(s <= 0.0 ? 1.0 : 0.0).d1))
    return Location::kink;
  return Location::interior;
}

ProjectionResult BSplineCurve::project_auto(const Vec3& p, const Options& options) const {
  const auto to_local = [&](std::size_t k, const std::array<double, 3>& t, std::array<double, 3>& local) {
    const ParamInterval& b = spans_[k];
    if (!b.contains(t[0])) return false;
    local = {(t[0] - b.tmin) / (b.tmax - b.tmin), 0.0, 0.0};
    return true;
  };
  const auto finish = [&](std::size_t k, ProjectionResult& r) {
    const ParamInterval& b = spans_[k];
    if (std::isfinite(r.distance)) {
      r.summary.location = locate(k, r.summary.location, r.params[0]);
      r.summary.on_boundary = r.summary.location == Location::endpoint;
      r.params[0] = global_of(r.params[0], b.tmin, b.tmax);
    }
    for (Minimum& m : r.minima) {
      m.location = locate(k, m.location, m.params[0]);
      m.params[0] = global_of(m.params[0], b.tmin, b.tmax);
    }
    for (auto& step : r.trace) step[0] *= b.tmax - b.tmin;
  };
  const auto direct = [](std::size_t, const Options&, double) { return std::optional<ProjectionResult>{}; };
  return nearest_piece(pieces_, tree_, p, options, to_local, finish, direct);
}

// ---- compiling -----------------------------------------------------------------------------------

std::shared_ptr<const CompiledGeometry> compile_bspline_surface(const GeometryDefinition& def,
                                                                const formula::CompileLimits& limits) {
  const BSplineNet& net = def.bspline;
  if (net.degree.size() != 2) throw GeometryError("bad_bspline", "degree", -1, "degree must be [p, q]");
  if (net.knots.size() != 2) throw GeometryError("bad_bspline", "knots", -1, "knots must have u and v");
  std::size_t count = 0;
  for (const auto& row : net.control_points) count += row.size();
  if (count > kMaxControlPoints)
    throw GeometryError("bad_bspline", "control_points", -1,
                        "control_points has " + std::to_string(count) + " points; the limit is " +
                            std::to_string(kMaxControlPoints));
  nurbs::SurfaceOrError s = nurbs::make_surface({net.degree[0], net.degree[1]}, net.knots[0], net.knots[1],
                                                net.control_points, net.weights, kMaxControlPoints);
  if (!s.surface) throw bspline_error(s.error);
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  return std::make_shared<BSplineSurface>(def, std::move(*s.surface), limits, budget);
}

std::shared_ptr<const CompiledGeometry> compile_bspline_curve(const GeometryDefinition& def,
                                                              const formula::CompileLimits& limits) {
  const BSplineNet& net = def.bspline;
  if (net.degree.size() != 1) throw GeometryError("bad_bspline", "degree", -1, "degree must be one number");
  if (net.knots.size() != 1 || net.control_points.size() != 1 || net.weights.size() > 1)
    throw GeometryError("bad_bspline", "control_points", -1, "a curve has one list of control points");
  nurbs::CurveOrError c =
      nurbs::make_curve(net.degree[0], net.knots[0], net.control_points[0],
                        net.weights.empty() ? std::vector<double>{} : net.weights[0], kMaxControlPoints);
  if (!c.curve) throw bspline_error(c.error);
  CompileBudget budget(limits.deadline, limits.max_geometry_bytes);
  return std::make_shared<BSplineCurve>(def, std::move(*c.curve), limits, budget);
}

}  // namespace footpoint
