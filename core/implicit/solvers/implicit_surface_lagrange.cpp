#include "implicit/solvers/implicit_surface_lagrange.hpp"

#include <array>
#include <cmath>
#include <cstddef>

#include "geometry/dense_solve.hpp"
#include "implicit/geometry/lagrange_step.hpp"

namespace footpoint::surface_implicit {

Mat3 lagrangian_hessian(const ImplicitSurfaceJet& j, double l) {
  Mat3 a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = (r == c ? 1.0 : 0.0) + l * j.hess[r][c];
  return a;
}

double TangentForm::least_eigenvalue() const {
  return 0.5 * (a11 + a22) - std::sqrt(0.25 * (a11 - a22) * (a11 - a22) + a12 * a12);
}

TangentForm tangent_form(const Mat3& a, Vec3 n) {
  const Vec3 helper = std::fabs(n.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 t1 = cross(n, helper) / norm(cross(n, helper)), t2 = cross(n, t1);
  return {dot(t1, a * t1), dot(t1, a * t2), dot(t2, a * t2)};
}

namespace {

Vec3 axis_vector(int axis) {
  Vec3 e{0.0, 0.0, 0.0};
  e[axis] = 1.0;
  return e;
}

// At a solution whose Newton system is singular (p at a centre of curvature of the foot, where
// I + l H is singular along the surface), the residuals themselves say it is one: |X - p + l grad f|
// and |f| / |grad f| at the rounding level of |X| and |p|.
bool solved(const ImplicitSurfaceJet& j, Vec3 r, Vec3 x, Vec3 p) {
  const double scale = 64.0 * 0x1p-52 * std::max({1.0, norm(x), norm(p)});
  const double g = norm(j.grad);
  return norm(r) <= scale && g > 0.0 && std::fabs(j.f) <= scale * g;
}

// Shortens the step (dx, dl) to max_step; false once that has happened more than 8 times.
bool limit_step(Vec3& dx, double* dl, int n, double max_step, int& shortened) {
  const double length = norm(dx);
  if (!(length > max_step)) return true;
  const double s = max_step / length;
  dx = s * dx;
  for (int i = 0; i < n; ++i) dl[i] *= s;
  return ++shortened <= 8;
}

}  // namespace

namespace {

// The Newton iteration both systems share, from x0 with its jet j and the multipliers l:
// `solve(j, x, l, dx, dl, r)` gives the step (dl the multipliers' increments) and the first block's
// residual r, false where the system is singular; `snap(x)` puts an iterate back on its
// constraints exactly.
template <std::size_t M, class Solve, class Snap>
SurfaceMinimum newton_loop(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 x0, ImplicitSurfaceJet j,
                           std::array<double, M> l, double max_step, const curve::IterationControl& control,
                           Solve&& solve, Snap&& snap) {
  SurfaceMinimum out;
  out.x = x0;
  double previous = curve::kInfinity;
  int shortened = 0;
  for (int n = 0; n < control.max_iterations; ++n) {
    Vec3 dx, r;
    std::array<double, M> dl{};
    if (!solve(j, out.x, l, dx, dl, r)) {
      out.converged = n > 0 && solved(j, r, out.x, p);
      break;
    }
    if (!limit_step(dx, dl.data(), static_cast<int>(M), max_step, shortened)) return out;
    out.x += dx;
    snap(out.x);
    for (std::size_t i = 0; i < M; ++i) l[i] += dl[i];
    out.step = norm(dx);
    out.iterations = n + 1;
    control.record(dx.x, dx.y, dx.z);
    if (!is_finite(out.x) || !std::isfinite(l[0])) return out;
    j = equation.jet(out.x);
    if (control.stop(out.step, norm(out.x), previous)) {
      out.converged = std::isfinite(j.f);
      break;
    }
  }
  out.multiplier = l[0];
  return out;
}

}  // namespace

SurfaceMinimum lagrange_newton_interior(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 x0,
                                        double max_step, const curve::IterationControl& control) {
  const ImplicitSurfaceJet j0 = equation.jet(x0);
  const double g2 = norm2(j0.grad);
  if (!(g2 > 0.0)) return {x0};
  const std::array<double, 1> l0{dot(j0.grad, p - x0) / g2};
  auto solve = [&](const ImplicitSurfaceJet& j, Vec3 x, const std::array<double, 1>& l, Vec3& dx,
                   std::array<double, 1>& dl, Vec3& r) {
    const Mat3 a = lagrangian_hessian(j, l[0]);
    Matrix<4> m{};
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 3; ++c) m[i][c] = a[i][c];
      m[i][3] = m[3][i] = j.grad[i];
    }
    r = x - p + l[0] * j.grad;
    Vector<4> b{-r.x, -r.y, -r.z, -j.f};
    if (!dense_solve<4>(m, b)) return false;
    dx = {b[0], b[1], b[2]};
    dl[0] = b[3];
    return true;
  };
  return newton_loop(equation, p, x0, j0, l0, max_step, control, solve, [](Vec3&) {});
}

SurfaceMinimum lagrange_newton_face(const ImplicitSurfaceEquation& equation, Vec3 p, Vec3 x0, int axis,
                                    double value, double max_step, const curve::IterationControl& control) {
  x0[axis] = value;
  const Vec3 e = axis_vector(axis);
  const ImplicitSurfaceJet j0 = equation.jet(x0);
  // Least-squares multipliers of p - X = l grad f + m e_k: l from the in-plane part.
  Vec3 g_plane = j0.grad, r_plane = p - x0;
  g_plane[axis] = r_plane[axis] = 0.0;
  const double gp2 = norm2(g_plane);
  if (!(gp2 > 0.0)) return {x0};
  const double l = dot(g_plane, r_plane) / gp2;
  const std::array<double, 2> l0{l, (p - x0)[axis] - l * j0.grad[axis]};
  // The curve {f = 0} ∩ {x_k = c}, multipliers (l, m): X - p + l grad f + m e_k = 0.
  auto solve = [&](const ImplicitSurfaceJet& j, Vec3 x, const std::array<double, 2>& lm, Vec3& dx,
                   std::array<double, 2>& dl, Vec3& r) {
    r = x - p + lm[0] * j.grad + lm[1] * e;
    LagrangeStep step;
    if (!lagrange_step(lagrangian_hessian(j, lm[0]), j.grad, e, r, j.f, x[axis] - value, step)) return false;
    dx = step.dx;
    dl = {step.dl1, step.dl2};
    return true;
  };
  // Exactly on the plane (the step keeps it there up to rounding).
  return newton_loop(equation, p, x0, j0, l0, max_step, control, solve, [&](Vec3& x) { x[axis] = value; });
}

Location box_location(const Box3& box, Vec3 x, double slack) {
  int at = 0;
  for (int k = 0; k < 3; ++k)
    at += (std::fabs(x[k] - box.lo[k]) <= slack || std::fabs(x[k] - box.hi[k]) <= slack) ? 1 : 0;
  return at == 0   ? Location::interior
         : at == 1 ? Location::box_face
         : at == 2 ? Location::box_edge
                   : Location::box_corner;
}

ProjectionResult implicit_surface_result(const ImplicitSurfaceEquation& equation, const Box3& box, Vec3 p,
                                         Vec3 x, const char* method) {
  ProjectionResult r;
  r.dim = 3;
  r.num_params = 0;
  r.foot = {x.x, x.y, x.z};
  r.distance = norm(p - x);
  r.summary.method = method;
  const ImplicitSurfaceJet j = equation.jet(x);
  const double g = norm(j.grad);
  r.summary.equation_residual[0] = g > 0.0 ? std::fabs(j.f) / g : (j.f == 0.0 ? 0.0 : curve::kInfinity);
  r.summary.location = box_location(box, x);
  // Orthogonality in the directions the foot is free to move in: all three inside the box, the
  // face's plane on a face (p - x = l grad f + m e_k there); none on an edge or at a corner.
  Vec3 d = p - x, n = j.grad;
  int free = 3;
  for (int k = 0; k < 3; ++k)
    if (x[k] == box.lo[k] || x[k] == box.hi[k]) {
      d[k] = n[k] = 0.0;
      --free;
    }
  const double dn = norm(d), nn = norm(n);
  r.summary.orthogonality[0] = free >= 2 && dn > 0.0 && nn > 0.0 ? norm(cross(d, n)) / (dn * nn) : 0.0;
  r.summary.on_boundary = r.summary.location != Location::interior;
  return r;
}

}  // namespace footpoint::surface_implicit
