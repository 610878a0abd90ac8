// Small dense linear systems A x = b (N <= 5) by Gaussian elimination with partial pivoting, on
// the stack: the Newton steps on curves (the Lagrange system of `auto` is 5 x 5) allocate nothing.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace footpoint {

template <int N>
using Matrix = std::array<std::array<double, N>, N>;
template <int N>
using Vector = std::array<double, N>;

// Solves A x = b in place (b becomes x). Returns false when a pivot is below
// pivot_tolerance * max|A| (64 eps: numerically singular), in which case b is left unspecified.
template <int N>
bool dense_solve(Matrix<N> a, Vector<N>& b,
                 double pivot_tolerance = 64.0 * std::numeric_limits<double>::epsilon()) {
  double scale = 0.0;
  for (const auto& row : a)
    for (double v : row) scale = std::max(scale, std::fabs(v));  // a NaN entry is passed over, as by fmax
  if (!(scale > 0.0) || !std::isfinite(scale)) return false;
  const double tiny = pivot_tolerance * scale;
  for (int k = 0; k < N; ++k) {
    int pivot = k;
    for (int i = k + 1; i < N; ++i)
      if (std::fabs(a[i][k]) > std::fabs(a[pivot][k])) pivot = i;
    if (!(std::fabs(a[pivot][k]) > tiny)) return false;
    if (pivot != k) {
      std::swap(a[pivot], a[k]);
      std::swap(b[pivot], b[k]);
    }
    for (int i = k + 1; i < N; ++i) {
      const double m = a[i][k] / a[k][k];
      if (m == 0.0) continue;
      for (int j = k; j < N; ++j) a[i][j] -= m * a[k][j];
      b[i] -= m * b[k];
    }
  }
  for (int k = N - 1; k >= 0; --k) {
    double s = b[k];
    for (int j = k + 1; j < N; ++j) s -= a[k][j] * b[j];
    b[k] = s / a[k][k];
    if (!std::isfinite(b[k])) return false;
  }
  return true;
}

}  // namespace footpoint
