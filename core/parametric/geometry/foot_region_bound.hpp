// The foot region bound: a rigorous lower bound of f(t) = ½|s(t) - p|² over a box H of the
// parameters that holds a point z where ∇f(z) is (nearly) zero, from the data at z (s(z), J(z)
// and ∇f(z), enclosed) and an enclosure of the second partials of s over H, with no bound of
// ∇²f over H. It closes the boxes around a solved foot point that the second-order bound of
// distance_bound.hpp closes only once they are small enough for an interval enclosure of
// ∇²f = JᵀJ + Σ (s_k - p_k) ∇²s_k to be positive definite (the cluster effect: Du and Kearfott,
// "The cluster problem in multivariate global optimization", J. Global Optim. 5 (1994) 253-265).
//
// The mathematics. Measure h = t - z in the metric of the surface at z: with G = JᵀJ ≈ L Lᵀ
// (Cholesky) and w = Lᵀ h, ρ = |w| is the length of J h up to the factor σ (|J h| >= σ ρ, σ ~ 1
// bounded below rigorously). Taylor's theorem with the integral remainder on the segment z -> t,
// which lies in H (H convex):
//   s(t) - s(z) = J h + R,   R = ∫₀¹ (1-τ) ∂²s(z + τh)[h, h] dτ,
//   f(t) - f(z) = ½ |s(t) - s(z)|² + (s(t) - s(z))·(s(z) - p)
//              = ½ |J h + R|² + hᵀ∇f(z) + R·(s(z) - p).
// In the coordinates w the second partials are T_ij = Σ_ab C_ai C_bj ∂_a∂_b s (C = L⁻ᵀ), so
// ∂²s[h, h] = Σ w_i w_j T_ij, and over H:
//   |∂²s[h, h]| <= M ρ²,          M = λmax of the matrix of max |T_ij| (a nonnegative matrix),
//   Σ w_i w_j T_ij·(s(z) - p) >= λ ρ²,  λ a lower bound of the least eigenvalue of [T_ij·(s(z) - p)],
//   hᵀ∇f(z) >= -γ ρ,              γ = Σ_a |row a of C| |∂_a f(z)| over the terms h_a ∂_a f(z)
//                                   that may be negative on H (none where z is a minimiser on an
//                                   edge of the domain and H lies on the domain's side).
// With ρ <= ρmax on H and a = σ - ½ M ρmax > 0: |J h + R| >= σρ - ½Mρ² >= a ρ, hence
//   f(t) - f(z) >= ½ (a² + λ) ρ² - γ ρ >= -γ² / (2 (a² + λ))   where c = a² + λ > 0.
// On a surface (N = 2) whose J is far from isometric, M and λ are each the worst over all
// directions: M pairs the soft direction's bending (T scaled by 1/σmin²) with the stiff
// direction's reach ρmax. Where a² + λ <= 0 the bound is taken ray by ray from z instead: on the
// ray through a point of the box's boundary with w = Lᵀh there, |R| <= ψρ with
// ψ = ½ Σ |w_i||w_j| max|T_ij| / |w| (the ratio grows along the ray), and R·(s(z) - p) >= ½Λρ²
// with Λ = hᵀNh/|w|², N ⊇ ∂²s·(s(z) - p) over H in the parameters; c = min over the rays of
// (σ - ψ)² + Λ (the boundary cut into pieces, each bounded from its ends).
// The bound is the same for every box inside H: f(z) less γ²/(2c), with γ at the rounding level
// of the solved foot point. It needs no convexity of f beyond what the surface's own geometry
// gives: for a point near the surface (|s(z) - p| small against the radius of curvature, so λ is
// small) it holds while ½ M ρmax < σ, i.e. on the region where the parametrisation is injective
// by the inverse function theorem's quantitative form, which is the local reach argument of
// Federer ("Curvature measures", Trans. Amer. Math. Soc. 93 (1959) 418-491, Theorem 4.8)
// restricted to H.
//
// Rounding: the enclosures are rigorous; the arithmetic here is round to nearest, and each
// quantity is enlarged by kBoundRounding times the magnitudes it sums (distance_bound.hpp).
#pragma once
#include <array>

#include "parametric/geometry/box_enclosure.hpp"
#include "parametric/geometry/distance_bound.hpp"

namespace footpoint {

// A lower bound of f over the box [lo, hi], which must hold the segment from z to each of its
// points (z inside it, or [lo, hi] the hull of a box and z), given s and J at z (`at_z`), f and
// ∇f at z (`f_z`), and `d2`, whose second partials (d2_mid ± d2_rad) hold those of s over
// [lo, hi]. -inf where the bound does not hold (d2 not smooth, J(z) singular, or the box too
// large for its second partials: a <= 0 or c <= 0 above).
template <int N>
double foot_region_lower_bound(const PointEnclosure<N>& at_z, const GradientEnclosure<N>& f_z,
                               const Params<N>& z, const BoxEnclosure<N>& d2, const Params<N>& lo,
                               const Params<N>& hi, const Vec3& p);

}  // namespace footpoint
