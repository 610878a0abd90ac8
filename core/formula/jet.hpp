// Forward-mode Taylor "jets": a value together with its exact partial derivatives with respect to
// N input variables, propagated through every operation by the chain rule (Faà di Bruno's formula
// up to third order). No finite differences anywhere: derivatives are exact to rounding.
#pragma once
#include <array>
#include <cstddef>

namespace footpoint::formula {

// Value, gradient and Hessian (second-order jet). The Hessian is stored as a full symmetric
// N x N matrix; N is 1 (curves), 2 (surfaces) or 3 (implicit equations in x, y, z).
template <int N>
struct Jet2 {
  double v = 0.0;
  std::array<double, N> g{};
  std::array<std::array<double, N>, N> h{};
};

// Value and all partial derivatives up to third order (third-order jet); used off the hot path
// (the hybrid method's switching test differentiates the Newton map, eq. (24) of the hybrid paper).
template <int N>
struct Jet3 {
  double v = 0.0;
  std::array<double, N> g{};
  std::array<std::array<double, N>, N> h{};
  std::array<std::array<std::array<double, N>, N>, N> t{};
};

}  // namespace footpoint::formula
