#include "parametric/geometry/foot_region_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace footpoint {

namespace {

constexpr double kNoBound = -std::numeric_limits<double>::infinity();
constexpr double kUp = 1.0 + kBoundRounding;  // enlarges an upper bound by its rounding

// The least eigenvalue of a symmetric 2 x 2 matrix whose entries lie in [m_ij - r_ij, m_ij + r_ij],
// bounded below: (a + c)/2 - sqrt(((a - c)/2)² + b²) falls as |a - c| and |b| grow.
double least_eigenvalue_lower(double m00, double r00, double m01, double r01, double m11, double r11) {
  const double half_sum = 0.5 * ((m00 - r00) + (m11 - r11));
  const double half_diff = 0.5 * (std::abs(m00 - m11) + r00 + r11);
  const double b = std::abs(m01) + r01;
  const double root = std::sqrt(half_diff * half_diff + b * b) * kUp;
  const double lambda = half_sum - root;
  return lambda - kBoundRounding * (std::abs(half_sum) + root);
}

// The bound direction by direction (N = 2). Along a ray h = r ĥ from z, with w = Lᵀh, ρ = |w|:
//   |J h + R| >= (σ - ψ) ρ,  ψ >= ½ Σ_ij |w_i| |w_j| m_ij / |w| at the ray's end on the box (m_ij
//   bounds of |T_ij| over the box: |R| <= ½ Σ |w_i||w_j| m_ij, and the ratio grows along the ray);
//   R·(s(z) - p) >= ½ hᵀ N h = ½ Λ ρ²,  Λ <= hᵀ N h / |w|² (N_ab ⊇ ∂_a∂_b s·(s(z) - p) over the box);
// so f(t) - f(z) >= ½ ((σ - ψ)² + Λ) ρ² - γρ on the ray, and c = the least (σ - ψ)² + Λ over
// the rays replaces a² + λ, which pairs the largest |T| with the farthest corner and the least
// curvature with every direction. The ray ends cover the box's sides; a side not through z,
// h_a = c with h_b = x in [l, u], is cut into kSideSteps pieces; w is affine in x, so on a piece
// |w_i| is at most its larger end value, and |w|² = (L00 h0 + L10 h1)² + (L11 h1)² (a sum of
// squares) lies between its least value and its larger end value. A side through z adds no ray of
// its own: its points are multiples of its corners, which lie on the other sides. -inf where some
// ray has σ <= ψ. With `lambda` (a lower bound of Λ over all rays), also (σ - max ψ)² + λ: the
// larger of the two.
double least_curvature_by_direction(const double (&L)[2][2], const double (&m)[2][2],
                                    const double (&n_lo)[2][2], const double (&n_hi)[2][2], double sigma,
                                    double lambda, const Params<2>& lo, const Params<2>& hi,
                                    const Params<2>& z) {
  constexpr int kSideSteps = 8;
  double least = std::numeric_limits<double>::infinity(), psi_max = 0.0;
  for (int a = 0; a < 2; ++a) {
    const int b = 1 - a;
    const std::size_t ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    for (const double side : {lo[ua], hi[ua]}) {
      const double c = side - z[ua];
      if (c == 0.0) continue;
      auto w_at = [&](double x, double(&w)[2]) {
        const double h0 = a == 0 ? c : x, h1 = a == 0 ? x : c;
        w[0] = L[0][0] * h0 + L[1][0] * h1;
        w[1] = L[1][1] * h1;
      };
      // |w|² along the side is least at x = -L00 L10 c / (L10² + L11²) (a = 0), -L10 c / L00 (a = 1)
      const double g11 = L[1][0] * L[1][0] + L[1][1] * L[1][1];
      const double vertex = a == 0 ? -L[0][0] * L[1][0] * c / g11 : -L[1][0] * c / L[0][0];
      const double least_at_vertex =
          a == 0 ? (L[0][0] * L[1][1] * c) * (L[0][0] * L[1][1] * c) / g11 : (L[1][1] * c) * (L[1][1] * c);
      const double l = lo[ub] - z[ub], u = hi[ub] - z[ub];
      double w_prev[2];
      w_at(l, w_prev);
      for (int k = 0; k < kSideSteps; ++k) {
        const double x0 = l + (u - l) * k / kSideSteps;
        const double x1 = k + 1 == kSideSteps ? u : l + (u - l) * (k + 1) / kSideSteps;
        double w_next[2];
        w_at(x1, w_next);
        const double q0 = w_prev[0] * w_prev[0] + w_prev[1] * w_prev[1];
        const double q1 = w_next[0] * w_next[0] + w_next[1] * w_next[1];
        double q_lo = std::min(q0, q1);
        if (vertex > x0 && vertex < x1) q_lo = std::min(q_lo, least_at_vertex);
        q_lo *= 1.0 - 1e-9;
        const double q_hi = std::max(q0, q1) * (1.0 + 1e-9);
        if (!(q_lo > 0.0)) return kNoBound;
        // ψ on the piece
        const double W0 = std::max(std::abs(w_prev[0]), std::abs(w_next[0])) * kUp;
        const double W1 = std::max(std::abs(w_prev[1]), std::abs(w_next[1])) * kUp;
        const double num = 0.5 * (m[0][0] * W0 * W0 + 2.0 * m[0][1] * W0 * W1 + m[1][1] * W1 * W1) * kUp;
        const double psi = std::sqrt(num * num / q_lo) * kUp * kUp;
        if (!(psi < sigma)) return kNoBound;
        psi_max = std::max(psi_max, psi);
        // hᵀNh on the piece: c² N_aa + 2 c x N_ab + x² N_bb, each term at its least
        const double x_abs_lo = x0 <= 0.0 && x1 >= 0.0 ? 0.0 : std::min(std::abs(x0), std::abs(x1));
        const double x_abs_hi = std::max(std::abs(x0), std::abs(x1));
        auto least_product = [](double p_lo, double p_hi, double v_lo, double v_hi) {
          return std::min({p_lo * v_lo, p_lo * v_hi, p_hi * v_lo, p_hi * v_hi});
        };
        const double t_aa = c * c * n_lo[a][a];
        const double t_ab = least_product(2.0 * c * x0, 2.0 * c * x1, n_lo[a][b], n_hi[a][b]);
        const double t_bb =
            n_lo[b][b] >= 0.0 ? x_abs_lo * x_abs_lo * n_lo[b][b] : x_abs_hi * x_abs_hi * n_lo[b][b];
        const double quad = t_aa + t_ab + t_bb;
        const double quad_lo = quad - kBoundRounding * (std::abs(t_aa) + std::abs(t_ab) + std::abs(t_bb));
        const double curvature = quad_lo >= 0.0 ? quad_lo / q_hi : quad_lo / q_lo;
        const double margin = sigma - psi;
        least = std::min(least, margin * margin * (1.0 - 4.0 * kBoundRounding) +
                                    curvature * (curvature < 0.0 ? kUp : 1.0 - kBoundRounding));
        w_prev[0] = w_next[0];
        w_prev[1] = w_next[1];
      }
    }
  }
  const double margin = sigma - psi_max;
  return std::max(least, margin * margin * (1.0 - 4.0 * kBoundRounding) + lambda);
}

}  // namespace

template <int N>
double foot_region_lower_bound(const PointEnclosure<N>& at_z, const GradientEnclosure<N>& f_z,
                               const Params<N>& z, const BoxEnclosure<N>& d2, const Params<N>& lo,
                               const Params<N>& hi, const Vec3& p) {
  if (!at_z.valid || !d2.smooth) return kNoBound;
  // G = JᵀJ at the stored J, and its Cholesky factor L (lower triangular); C = L⁻ᵀ.
  double G[N][N];
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) G[i][j] = dot(at_z.ds[i], at_z.ds[j]);
  double L[N][N] = {}, C[N][N] = {};
  L[0][0] = std::sqrt(G[0][0]);
  if (!(L[0][0] > 0.0)) return kNoBound;
  if constexpr (N == 2) {
    L[1][0] = G[1][0] / L[0][0];
    const double l11sq = G[1][1] - L[1][0] * L[1][0];
    if (!(l11sq > 1e-12 * G[1][1])) return kNoBound;  // J nearly singular: no metric frame
    L[1][1] = std::sqrt(l11sq);
    // Lᵀ = [l00 l10; 0 l11], its inverse C = [1/l00, -l10/(l00 l11); 0, 1/l11]
    C[0][0] = 1.0 / L[0][0];
    C[0][1] = -L[1][0] / (L[0][0] * L[1][1]);
    C[1][1] = 1.0 / L[1][1];
  } else {
    C[0][0] = 1.0 / L[0][0];
  }

  // σ: |J C w| >= σ |w| for the exact J (within ds_rad of the stored one). K = J̃ C has nearly
  // orthonormal columns; λmin(KᵀK) >= 1 - ‖KᵀK - I‖_F, and √(1 - x) >= 1 - x on [0, 1]. The exact
  // JC differs from the computed K by E, |E_ki| <= Σ_a ds_rad_a,k |C_ai| + the rounding of K.
  Vec3 K[N], E[N];
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < 3; ++k) {
      double v = 0.0, magnitude = 0.0, e = 0.0;
      for (int a = 0; a < N; ++a) {
        v += at_z.ds[a][k] * C[a][i];
        magnitude += std::abs(at_z.ds[a][k] * C[a][i]);
        e += at_z.ds_rad[a][k] * std::abs(C[a][i]);
      }
      K[i][k] = v;
      E[i][k] = (e + kBoundRounding * magnitude) * kUp;
    }
  }
  double off = 0.0, e_frob = 0.0;
  for (int i = 0; i < N; ++i) {
    e_frob += norm2(E[i]);
    for (int j = 0; j < N; ++j) {
      const double kk = dot(K[i], K[j]) - (i == j ? 1.0 : 0.0);
      const double r = std::abs(kk) + kBoundRounding * (norm(K[i]) * norm(K[j]) + 1.0);
      off += r * r;
    }
  }
  const double sigma = (1.0 - std::sqrt(off) * kUp) - std::sqrt(e_frob) * kUp;
  if (!(sigma > 0.0)) return kNoBound;

  // T_ij = Σ_ab C_ai C_bj ∂_a∂_b s over the box, enclosed (mid ± rad); their magnitudes m_ij and
  // the enclosures n_ij ± r_ij of T_ij·(s(z) - p), with s(z) - p = e + δ, |δ_k| <= s_rad_k.
  const Vec3 e = at_z.s - p;
  double m[N][N], n[N][N], r[N][N];
  for (int i = 0; i < N; ++i) {
    for (int j = i; j < N; ++j) {
      Vec3 mid{}, rad{};
      for (int a = 0; a < N; ++a) {
        for (int b = 0; b < N; ++b) {
          const double coef = C[a][i] * C[b][j];
          if (coef == 0.0) continue;
          const int q = BoxEnclosure<N>::pair(a, b);
          for (int k = 0; k < 3; ++k) {
            mid[k] += coef * d2.d2_mid[static_cast<std::size_t>(q)][k];
            rad[k] += std::abs(coef) * (d2.d2_rad[static_cast<std::size_t>(q)][k] +
                                        kBoundRounding * std::abs(d2.d2_mid[static_cast<std::size_t>(q)][k]));
          }
        }
      }
      Vec3 bound{};
      double nm = 0.0, nr = 0.0, magnitude = 0.0;
      for (int k = 0; k < 3; ++k) {
        rad[k] *= kUp;
        bound[k] = std::abs(mid[k]) + rad[k];
        nm += mid[k] * e[k];
        magnitude += std::abs(mid[k] * e[k]);
        nr += rad[k] * std::abs(e[k]) + bound[k] * at_z.s_rad[k];
      }
      m[i][j] = m[j][i] = norm(bound) * kUp;
      n[i][j] = n[j][i] = nm;
      r[i][j] = r[j][i] = (nr + kBoundRounding * magnitude) * kUp;
    }
  }
  double M = 0.0, lambda = 0.0;
  if constexpr (N == 2) {
    const double half_diff = 0.5 * (m[0][0] - m[1][1]);
    M = (0.5 * (m[0][0] + m[1][1]) + std::sqrt(half_diff * half_diff + m[0][1] * m[0][1])) * kUp * kUp;
    lambda = least_eigenvalue_lower(n[0][0], r[0][0], n[0][1], r[0][1], n[1][1], r[1][1]);
  } else {
    M = m[0][0];
    lambda = n[0][0] - r[0][0];
  }

  // γ: hᵀ∇f(z) >= -γ ρ. A term h_a ∂_a f(z) of one sign over the box drops out (z on an edge
  // of the box with the gradient pointing into it: the first-order condition of a minimum on the
  // domain's boundary); each other term is at least -|h_a| (|g_a| + g_rad_a), and
  // |h_a| = |(C w)_a| <= |row a of C| ρ.
  double gamma = 0.0;
  for (int a = 0; a < N; ++a) {
    const double g_lo = f_z.g[a] - f_z.g_rad[a], g_hi = f_z.g[a] + f_z.g_rad[a];
    if ((lo[a] >= z[a] && g_lo >= 0.0) || (hi[a] <= z[a] && g_hi <= 0.0)) continue;
    double row = 0.0;
    for (int i = 0; i < N; ++i) row += C[a][i] * C[a][i];
    gamma += std::sqrt(row) * (std::abs(f_z.g[a]) + f_z.g_rad[a]);
  }
  gamma *= kUp * kUp;

  // ρmax: |w| = |C⁻¹(t - z)| at the box's farthest corner (the norm is convex). C⁻¹ = Lᵀ up to
  // the rounding of C, relative to the condition of L (<= 1e6 here, G11 - l10² > 1e-12 G11):
  // 1e-9 covers it.
  double rho_max = 0.0;
  for (int corner = 0; corner < (1 << N); ++corner) {
    double h[N];
    for (int a = 0; a < N; ++a) h[a] = ((corner >> a) & 1 ? hi[a] : lo[a]) - z[a];
    double w2 = 0.0;
    for (int i = 0; i < N; ++i) {
      double w = 0.0;
      for (int a = i; a < N; ++a) w += std::abs(L[a][i] * h[a]);  // (Lᵀh)_i = Σ_a L_ai h_a
      w2 += w * w;
    }
    rho_max = std::max(rho_max, std::sqrt(w2) * (1.0 + 1e-9));
  }

  // c: f(t) - f(z) >= ½ c ρ² - γρ on the box, from a = σ - ½Mρmax (|J h + R| >= a ρ) and λ, or
  // where they do not give c > 0, ray by ray (least_curvature_by_direction).
  const double a = sigma - 0.5 * M * rho_max * kUp;
  double c = a > 0.0 ? a * a * (1.0 - 4.0 * kBoundRounding) + lambda : kNoBound;
  if constexpr (N == 2) {
    if (!(c > 0.0)) {
      // N_ab ⊇ ∂_a∂_b s·(s(z) - p) over the box, in the parameters
      double n_lo[2][2], n_hi[2][2];
      for (int i = 0; i < 2; ++i)
        for (int j = i; j < 2; ++j) {
          const std::size_t q = static_cast<std::size_t>(BoxEnclosure<2>::pair(i, j));
          double mid = 0.0, rad = 0.0, magnitude = 0.0;
          for (int k = 0; k < 3; ++k) {
            const double dm = d2.d2_mid[q][k], dr = d2.d2_rad[q][k];
            mid += dm * e[k];
            magnitude += std::abs(dm * e[k]);
            rad += dr * std::abs(e[k]) + (std::abs(dm) + dr) * at_z.s_rad[k];
          }
          rad = (rad + kBoundRounding * magnitude) * kUp;
          n_lo[i][j] = n_lo[j][i] = mid - rad;
          n_hi[i][j] = n_hi[j][i] = mid + rad;
        }
      c = least_curvature_by_direction(L, m, n_lo, n_hi, sigma, lambda, lo, hi, z);
    }
  }
  if (!(c > 0.0)) return kNoBound;
  const double loss = gamma * gamma / (2.0 * c) * kUp * kUp;
  const double bound = f_z.f_lo - loss;
  return bound - kBoundRounding * (std::abs(f_z.f_lo) + loss);
}

template double foot_region_lower_bound<1>(const PointEnclosure<1>&, const GradientEnclosure<1>&,
                                           const Params<1>&, const BoxEnclosure<1>&, const Params<1>&,
                                           const Params<1>&, const Vec3&);
template double foot_region_lower_bound<2>(const PointEnclosure<2>&, const GradientEnclosure<2>&,
                                           const Params<2>&, const BoxEnclosure<2>&, const Params<2>&,
                                           const Params<2>&, const Vec3&);

}  // namespace footpoint
