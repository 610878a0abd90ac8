#include "mesh/curve_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "mesh/equidistribution.hpp"

namespace footpoint {

namespace {

// Fine intervals per segment (at least kMinFine) the measure is sampled on.
constexpr int kFinePerSegment = 8;
constexpr int kMinFine = 64;
// A singular point is put at an open end within kStallSpacings sample spacings of it, and spliced
// into a piece passing within kPassSpacings of it.
constexpr double kPassSpacings = 0.5;
constexpr double kStallSpacings = 4.0;
constexpr double kInfinityDistance = std::numeric_limits<double>::infinity();

// The direction of travel through vertex k of a polyline (the chord from its predecessor to its
// successor, one-sided at an open end).
Vec3 travel(const Mesh& mesh, const Polyline& line, std::size_t k) {
  const std::size_t n = line.vertices.size();
  const auto point = [&](std::size_t i) { return mesh.vertices[static_cast<std::size_t>(line.vertices[i])]; };
  const std::size_t before = k > 0 ? k - 1 : (line.closed ? n - 1 : k);
  const std::size_t after = k + 1 < n ? k + 1 : (line.closed ? 0 : k);
  return unit(point(after) - point(before));
}

// A traced piece as sample indices in walking order; a closed one returns to its first sample.
struct Piece {
  std::vector<std::int32_t> samples;
  bool closed = false;
};

double distance_to_segment(Vec3 x, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double length2 = norm2(ab);
  const double t = length2 > 0.0 ? std::clamp(dot(x - a, ab) / length2, 0.0, 1.0) : 0.0;
  return norm(x - (a + t * ab));
}

// Joins the singular point `s` to a piece: put at an open end within kStallSpacings of it (the
// pieces of discovery end next to the small unproved box around a singular point,
// implicit/seeding/curve_cells.hpp), else spliced between the two samples of each passage of the piece
// within half a spacing of it.
void join_singular_point(const CurveSamples& samples, std::int32_t s, Piece& piece) {
  const auto point = [&](std::int32_t i) { return samples.points[static_cast<std::size_t>(i)]; };
  const Vec3 x = point(s);
  const double h = samples.spacing;
  std::vector<std::int32_t>& list = piece.samples;
  if (!piece.closed) {
    const auto ends_near = [&](std::int32_t end) {
      return samples.kind[static_cast<std::size_t>(end)] == SampleKind::regular &&
             norm(point(end) - x) <= kStallSpacings * h;
    };
    const bool before_front = ends_near(list.front()), after_back = ends_near(list.back());
    if (before_front) list.insert(list.begin(), s);
    if (after_back) list.push_back(s);
    if (before_front || after_back) return;
  }
  const std::size_t size = list.size();
  const std::size_t count = piece.closed ? size : size - 1;  // segments; k joins list[k], list[k + 1]
  const auto near = [&](std::size_t k) {
    return distance_to_segment(x, point(list[k % size]), point(list[(k + 1) % size]));
  };
  // A loop is scanned from a segment that is not near, so that no passage is cut in two.
  std::size_t first = 0;
  if (piece.closed)
    while (first < count && near(first) <= kPassSpacings * h) ++first;
  if (first == count) return;      // the whole loop is within reach: too small to join
  std::vector<std::size_t> after;  // positions to splice s after, one per passage
  double best_distance = kInfinityDistance;
  std::size_t best = 0;
  for (std::size_t j = 0; j <= count; ++j) {
    const std::size_t k = first + j;
    const double d = j < count ? near(k) : kInfinityDistance;
    if (d <= kPassSpacings * h) {
      if (d < best_distance) {
        best = k % size;
        best_distance = d;
      }
    } else if (best_distance < kInfinityDistance) {
      after.push_back(best);
      best_distance = kInfinityDistance;
    }
  }
  std::sort(after.begin(), after.end());
  for (auto k = after.rbegin(); k != after.rend(); ++k)
    list.insert(list.begin() + static_cast<std::ptrdiff_t>(*k + 1), s);
}

// The open pieces that end at the singular point s are joined through it, two at a time, each
// end with the one leaving s most nearly opposite to it (a branch goes straight through a
// crossing); a piece whose two ends are so joined closes. The pieces of discovery end next to the
// small unproved box around a singular point (implicit/seeding/curve_cells.hpp), and join_singular_point put
// s at those ends.
void join_through(const CurveSamples& samples, std::int32_t s, std::vector<Piece>& pieces) {
  struct End {
    std::size_t piece;
    bool back;  // the piece's last sample is s (else its first)
    Vec3 away;  // from s along the piece
  };
  for (;;) {
    std::vector<End> ends;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const Piece& p = pieces[k];
      if (p.closed || p.samples.size() < 3) continue;
      const auto point = [&](std::int32_t i) { return samples.points[static_cast<std::size_t>(i)]; };
      if (p.samples.front() == s) ends.push_back({k, false, unit(point(p.samples[1]) - point(s))});
      if (p.samples.back() == s)
        ends.push_back({k, true, unit(point(p.samples[p.samples.size() - 2]) - point(s))});
    }
    if (ends.size() < 2) return;
    double best = 2.0;
    std::size_t a = 0, b = 0;
    for (std::size_t i = 0; i < ends.size(); ++i)
      for (std::size_t j = i + 1; j < ends.size(); ++j)
        if (dot(ends[i].away, ends[j].away) < best) best = dot(ends[i].away, ends[j].away), a = i, b = j;
    const End first = ends[a], second = ends[b];
    if (first.piece == second.piece) {  // both ends of one piece: a loop through s
      Piece& p = pieces[first.piece];
      p.samples.pop_back();
      p.closed = true;
      continue;
    }
    // pieces[first] ending at s, then pieces[second] leaving s.
    std::vector<std::int32_t> head = pieces[first.piece].samples, tail = pieces[second.piece].samples;
    if (!first.back) std::reverse(head.begin(), head.end());
    if (second.back) std::reverse(tail.begin(), tail.end());
    head.insert(head.end(), tail.begin() + 1, tail.end());
    pieces[first.piece].samples = std::move(head);
    pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(second.piece));
  }
}

}  // namespace

Mesh mesh_parametric_curve(const ParametricCurve& curve, int resolution) {
  const CurveFormulas& formulas = curve.formulas();
  const ParamInterval& domain = curve.domain();
  const int fine_count = std::max(kMinFine, kFinePerSegment * resolution);
  std::vector<FineInterval> fine(static_cast<std::size_t>(fine_count));
  Vec3 last_point, last_tangent;
  for (int k = 0; k <= fine_count; ++k) {
    const double t =
        k == fine_count ? domain.tmax : domain.tmin + (domain.tmax - domain.tmin) * k / fine_count;
    const CurveJet j = formulas.jet(t);
    if (k > 0) {
      FineInterval& f = fine[static_cast<std::size_t>(k - 1)];
      const double chord = norm(j.c - last_point);
      f.length = std::isfinite(chord) ? chord : 0.0;
      f.turn = turn_angle(last_tangent, j.d1);
    }
    last_point = j.c;
    last_tangent = j.d1;
  }
  const std::vector<double> ts = equidistributed_lines(domain.tmin, domain.tmax, fine, resolution);

  // Runs of finite vertices; a run of one vertex is left out.
  Mesh mesh;
  mesh.num_params = 1;
  std::vector<Vec3> derivative;
  Polyline line;
  auto finish_line = [&] {
    if (line.vertices.size() >= 2) {
      mesh.polylines.push_back(std::move(line));
    } else if (line.vertices.size() == 1) {
      mesh.vertices.pop_back();
      mesh.parameters.pop_back();
      derivative.pop_back();
    }
    line = Polyline{};
  };
  for (const double t : ts) {
    const CurveJet j = formulas.jet(t);
    if (!is_finite(j.c)) {
      finish_line();
      continue;
    }
    line.vertices.push_back(static_cast<std::int32_t>(mesh.vertices.size()));
    mesh.vertices.push_back(j.c);
    mesh.parameters.push_back(t);
    derivative.push_back(j.d1);
  }
  finish_line();
  // A closed curve's vertex at tmax is its vertex at tmin: dropped, and the polyline that ends there
  // continues into the one that starts at tmin (itself, when the curve is finite all along).
  if (curve.closure().closed && !mesh.polylines.empty() && mesh.parameters.front() == domain.tmin &&
      mesh.parameters.back() == domain.tmax && mesh.polylines.back().vertices.size() > 2) {
    Polyline& last = mesh.polylines.back();
    last.vertices.pop_back();
    mesh.vertices.pop_back();
    mesh.parameters.pop_back();
    derivative.pop_back();
    if (mesh.polylines.size() == 1) {
      last.closed = true;
    } else {
      Polyline& first = mesh.polylines.front();
      first.vertices.insert(first.vertices.begin(), last.vertices.begin(), last.vertices.end());
      mesh.polylines.pop_back();
    }
  }
  mesh.tangents.assign(mesh.vertices.size(), Vec3{});
  for (const Polyline& l : mesh.polylines)
    for (std::size_t k = 0; k < l.vertices.size(); ++k) {
      const auto v = static_cast<std::size_t>(l.vertices[k]);
      const Vec3 exact = unit(derivative[v]);
      mesh.tangents[v] = norm2(exact) > 0.0 ? exact : travel(mesh, l, k);
    }
  return mesh;
}

Mesh mesh_implicit_curve(const ImplicitCurve& curve, int resolution) {
  const CurveSamples& samples = curve.discovery().samples;
  const std::size_t n = samples.size();
  const auto at = [](std::int32_t i) { return static_cast<std::size_t>(i); };

  // The pieces as sample indices: open ones from their first sample, then the loops.
  std::vector<Piece> pieces;
  std::vector<bool> taken(n, false);
  auto follow = [&](std::int32_t first) {
    Piece piece;
    std::int32_t i = first;
    for (std::size_t steps = 0; steps < n && i >= 0 && !taken[at(i)]; ++steps) {
      taken[at(i)] = true;
      piece.samples.push_back(i);
      i = samples.next[at(i)];
    }
    piece.closed = i == first;
    if (piece.samples.size() >= 2) pieces.push_back(std::move(piece));
  };
  for (std::size_t i = 0; i < n; ++i)
    if (samples.prev[i] < 0 && samples.next[i] >= 0) follow(static_cast<std::int32_t>(i));
  for (std::size_t i = 0; i < n; ++i)
    if (!taken[i] && samples.next[i] >= 0) follow(static_cast<std::int32_t>(i));
  for (std::size_t s = 0; s < n; ++s)
    if (samples.kind[s] == SampleKind::singular_point) {
      for (Piece& piece : pieces) join_singular_point(samples, static_cast<std::int32_t>(s), piece);
      join_through(samples, static_cast<std::int32_t>(s), pieces);
    }

  std::size_t traced = 0;
  for (const Piece& p : pieces) traced += p.samples.size();
  const auto segments = static_cast<std::size_t>(resolution);
  const std::size_t every = std::max<std::size_t>(1, (traced + segments - 1) / segments);

  Mesh mesh;
  std::vector<std::int32_t> vertex(n, -1);
  auto vertex_of = [&](std::int32_t i) {
    if (vertex[at(i)] < 0) {
      vertex[at(i)] = static_cast<std::int32_t>(mesh.vertices.size());
      mesh.vertices.push_back(samples.points[at(i)]);
    }
    return vertex[at(i)];
  };
  for (std::size_t i = 0; i < n; ++i)
    if (samples.kind[i] == SampleKind::singular_point)
      mesh.singular_points.push_back(vertex_of(static_cast<std::int32_t>(i)));
  for (const Piece& piece : pieces) {
    const std::size_t size = piece.samples.size();
    Polyline line;
    line.closed = piece.closed;
    for (std::size_t k = 0; k < size; ++k) {
      const std::int32_t i = piece.samples[k];
      const bool end = !piece.closed && (k == 0 || k + 1 == size);
      if (k % every == 0 || end || samples.kind[at(i)] != SampleKind::regular ||
          (piece.closed && size / every < 3))
        line.vertices.push_back(vertex_of(i));
    }
    mesh.polylines.push_back(std::move(line));
  }

  mesh.tangents.assign(mesh.vertices.size(), Vec3{});
  std::vector<bool> is_singular(mesh.vertices.size(), false);
  for (std::int32_t v : mesh.singular_points) is_singular[at(v)] = true;
  for (const Polyline& line : mesh.polylines)
    for (std::size_t k = 0; k < line.vertices.size(); ++k) {
      const auto v = at(line.vertices[k]);
      if (is_singular[v]) continue;
      const Vec3 along = travel(mesh, line, k);
      const Vec3 exact = unit(curve.equations().jet(mesh.vertices[v]).tangent());
      mesh.tangents[v] = norm2(exact) > 0.0 ? (dot(exact, along) < 0.0 ? -exact : exact) : along;
    }
  return mesh;
}

}  // namespace footpoint
