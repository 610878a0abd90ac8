#include "implicit/seeding/face_crossings.hpp"

#include <bit>
#include <cmath>
#include <limits>

#include "geometry/dense_solve.hpp"
#include "geometry/krawczyk.hpp"

namespace footpoint {
namespace {

using formula::Interval;
namespace iv = formula::interval;

// Where a sub-face is split along its longest free edge: off the centre by a ratio no grid of
// nice numbers shares.
constexpr double kSplit = 0.4921731;
// Bisections below the face and sub-faces examined per face before the search gives up.
constexpr int kMaxDepth = 60;
constexpr int kMaxSubFaces = 256;
// A Krawczyk image this much narrower than its sub-face in every free coordinate replaces it
// (it holds every zero of the sub-face) instead of a bisection.
constexpr double kShrink = 0.7;

// N free coordinates and N equations: the first N of f1, f2.
template <int N>
class FaceSolver {
 public:
  FaceSolver(const ImplicitEquations& eq, int axis, std::vector<FaceCrossing>& out, std::size_t& evaluations)
      : eq_(eq), out_(out), evaluations_(evaluations) {
    int n = 0;
    for (int k = 0; k < 3 && n < N; ++k)
      if (k != axis) free_[n++] = k;
  }

  bool run(const Box3& face) {
    struct Item {
      Box3 box;
      int depth;
    };
    std::vector<Item> stack{{face, 0}};
    int examined = 0;
    while (!stack.empty()) {
      const Item q = stack.back();
      stack.pop_back();
      if (++examined > kMaxSubFaces || q.depth > kMaxDepth) return false;
      Box3 next;
      switch (examine(q.box, next)) {
        case Step::done:
          break;
        case Step::failed:
          return false;
        case Step::shrunk:
          stack.push_back({next, q.depth + 1});
          break;
        case Step::split: {
          const auto [a, b] = split(q.box);
          stack.push_back({a, q.depth + 1});
          stack.push_back({b, q.depth + 1});
          break;
        }
      }
    }
    return true;
  }

 private:
  enum class Step { done, failed, shrunk, split };

  IntervalVector<N> free_box(const Box3& q) const {
    IntervalVector<N> x{};
    for (int i = 0; i < N; ++i) x[i] = {q.lo[free_[i]], q.hi[free_[i]]};
    return x;
  }
  Vector<N> free_point(Vec3 x) const {
    Vector<N> m{};
    for (int i = 0; i < N; ++i) m[i] = x[free_[i]];
    return m;
  }
  IntervalVector<N> values_at(Vec3 x) {
    ++evaluations_;
    const std::array<Interval, 2> f = eq_.value_enclosure({x, x});
    IntervalVector<N> g{};
    for (int i = 0; i < N; ++i) g[i] = f[i];
    return g;
  }

  std::pair<Box3, Box3> split(const Box3& q) const {
    int k = free_[0];
    for (int i = 1; i < N; ++i)
      if (q.hi[free_[i]] - q.lo[free_[i]] > q.hi[k] - q.lo[k]) k = free_[i];
    const double s = q.lo[k] + kSplit * (q.hi[k] - q.lo[k]);
    Box3 a = q, b = q;
    a.hi[k] = s;
    b.lo[k] = s;
    return {a, b};
  }

  // Newton on the face from x (free coordinates only); true when it converged inside q: its step
  // fell to the rounding level, or stopped shrinking once below 1e-9 of |x| (the noise of an
  // ill-conditioned system).
  bool newton(const Box3& q, Vec3& x) const {
    double previous = std::numeric_limits<double>::infinity();
    for (int n = 0; n < 32; ++n) {
      const ImplicitJet j = eq_.jet(x);
      Matrix<N> a{};
      Vector<N> r{};
      for (int i = 0; i < N; ++i) {
        r[i] = -j.f[i];
        for (int c = 0; c < N; ++c) a[i][c] = j.grad[i][free_[c]];
      }
      if (!dense_solve<N>(a, r)) return false;
      double step = 0.0;
      for (int i = 0; i < N; ++i) {
        x[free_[i]] += r[i];
        step = std::fmax(step, std::fabs(r[i]));
      }
      if (!is_finite(x)) return false;
      const double size = std::fmax(1.0, norm(x));
      if (step <= 1e-15 * size || (step <= 1e-9 * size && step > 0.5 * previous)) return q.contains(x);
      previous = step;
    }
    return false;
  }

  Step examine(const Box3& q, Box3& next) {
    ++evaluations_;
    const std::array<Interval, 2> range = eq_.value_enclosure(q);
    for (int i = 0; i < N; ++i)
      if (range[i].excludes_zero()) return Step::done;
    ++evaluations_;
    const ImplicitIntervalJet j = eq_.interval_gradient(q);
    if (!j.smooth) return Step::failed;
    const Vec3 c = q.center();
    const Vector<N> m = free_point(c);
    const IntervalVector<N> gm = values_at(c);
    const IntervalVector<N> x = free_box(q);
    IntervalMatrix<N> a{};
    for (int i = 0; i < N; ++i) {
      Interval mean = gm[i];  // the mean value form about the centre
      for (int k = 0; k < N; ++k) {
        a[i][k] = j.grad[i][free_[k]];
        mean = iv::add(mean, iv::mul(a[i][k], iv::sub(x[k], iv::point(m[k]))));
      }
      if (mean.excludes_zero()) return Step::done;
    }
    // Regular: every matrix of the enclosure is nonsingular (a single-use expression of its entries).
    const Interval det =
        N == 1 ? a[0][0] : iv::sub(iv::mul(a[0][0], a[N - 1][N - 1]), iv::mul(a[0][N - 1], a[N - 1][0]));
    if (!det.excludes_zero()) return Step::split;
    const KrawczykResult<N> k = krawczyk<N>(x, m, gm, a);
    if (k.verdict == KrawczykVerdict::no_zero) return Step::done;
    // K(q) ∩ q holds every zero in q: the next box when it is much smaller.
    Box3 shrunk = q;
    bool narrower = true;
    for (int i = 0; i < N; ++i) {
      const Interval s = iv::intersect(k.image[i], x[i]);
      shrunk.lo[free_[i]] = s.lo;
      shrunk.hi[free_[i]] = s.hi;
      narrower = narrower && s.hi - s.lo <= kShrink * (x[i].hi - x[i].lo);
    }
    // Exactly one point in q: Newton gives it (else a smaller box is tried); the contraction bound
    // about it, a tight box.
    Vec3 p = c;
    bool found = k.verdict == KrawczykVerdict::unique_zero && newton(q, p);
    if (!found && k.verdict == KrawczykVerdict::unique_zero) {
      p = shrunk.center();
      found = newton(q, p);
    }
    if (!found) {
      if (!narrower) return Step::split;
      next = shrunk;
      return Step::shrunk;
    }
    const KrawczykResult<N> tight = krawczyk<N>(x, free_point(p), values_at(p), a);
    Box3 e = q;
    for (int i = 0; i < N; ++i) {
      const int f = free_[i];
      if (tight.contraction < 1.0) {
        e.lo[f] = std::fmax(q.lo[f], formula::down(p[f] - tight.radius, 1));
        e.hi[f] = std::fmin(q.hi[f], formula::up(p[f] + tight.radius, 1));
      } else {
        e.lo[f] = std::fmax(q.lo[f], k.image[i].lo);
        e.hi[f] = std::fmin(q.hi[f], k.image[i].hi);
      }
    }
    out_.push_back({p, e});
    return Step::done;
  }

  const ImplicitEquations& eq_;
  std::vector<FaceCrossing>& out_;
  std::size_t& evaluations_;
  std::array<int, N> free_{};
};

}  // namespace

bool locate_face_crossings(const ImplicitEquations& equations, const Box3& face, int axis,
                           std::vector<FaceCrossing>& out, std::size_t& evaluations) {
  if (equations.planar()) return FaceSolver<1>(equations, axis, out, evaluations).run(face);
  return FaceSolver<2>(equations, axis, out, evaluations).run(face);
}

std::size_t FaceCrossingCache::Hash::operator()(const Key& k) const {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
  for (std::uint64_t w : k.bits) h = (h ^ w) * 1099511628211ull;
  return static_cast<std::size_t>(h);
}

bool FaceCrossingCache::locate(const Box3& face, int axis, std::vector<FaceCrossing>& out,
                               std::size_t& evaluations) {
  Key key{};
  for (int k = 0; k < 3; ++k) {
    key.bits[static_cast<std::size_t>(2 * k)] = std::bit_cast<std::uint64_t>(face.lo[k]);
    key.bits[static_cast<std::size_t>(2 * k + 1)] = std::bit_cast<std::uint64_t>(face.hi[k]);
  }
  key.bits[0] ^= static_cast<std::uint64_t>(axis);  // lo == hi on the axis: room for it
  auto [it, inserted] = faces_.try_emplace(key);
  if (inserted)
    it->second.decided = locate_face_crossings(equations_, face, axis, it->second.crossings, evaluations);
  out.insert(out.end(), it->second.crossings.begin(), it->second.crossings.end());
  return it->second.decided;
}

}  // namespace footpoint
