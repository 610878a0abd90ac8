#!/usr/bin/python3
"""Reference nearest points on NURBS curves and surfaces (issue 35's bspline_curve and
bspline_surface), computed independently of footpoint's C++ code: tests/data/nurbs_projection_cases.json.

Method (Debian's python3 and python3-mpmath only; every input is a binary double, read exactly):
  1. Exact pieces. On every non-empty knot span the B-spline basis functions are polynomials; they
     are built as polynomials with exact rational coefficients by the Cox-de Boor recurrence
     (tests/tools/gen_nurbs_refs.py's polynomial machinery), shifted to the span's local parameter,
     and multiplied out with the weighted control points: per span, the homogeneous numerator
     (w x, w y, w z) and the weight w as polynomials (bivariate for surfaces) with Fraction
     coefficients; the point is numerator / w, its derivatives to second order by the quotient rule.
     Those coefficients are rounded once to doubles for the search and to 50-digit mpmath numbers
     for the refinement.
  2. Cells. The parameter domain [U_p, U_n] (per direction) is cut at the interior knots of
     multiplicity >= degree, where the curve or surface may be only C0; inside a cell it is C1 and
     f = |S - p|^2 / 2 is smooth piece by piece. The global minimum of f over the closed domain is a
     KKT point of f over some cell (its interior, one of its edges or a corner).
  3. Start set: a dense grid (every knot span cut into SAMPLES pieces, knot lines included), f on it,
     and every discrete local minimum of f over its 8 (curves: 2) neighbours.
  4. From each start, in every cell that holds it: projected Newton over the cell's box in doubles
     (free coordinates by Newton or steepest descent, coordinates at a bound whose gradient points
     outwards held there, Armijo backtracking), then Newton at 50 digits (mpmath) on the free
     coordinates of the point it reached, to |step| < 1e-40: interior points solve grad f = 0, edge
     points the 1-D problem along the edge, corners are taken as they are.
  5. The smallest distance over all refined candidates is the reference; another candidate with a
     distinct foot within 1e-30 relative of it is reported as a tie. A start whose refinement ends
     at no KKT point (a degenerate minimum: the circle's centre) is dropped, and the generator
     stops if such a start is nearer than the reference.
  6. Closed forms (circle, sphere, torus written as NURBS): the distance and foot of the ideal shape
     are computed in closed form and the numeric answer must agree with them to 1e-14 (the weights
     sqrt(2)/2 are doubles, so the NURBS of the file differs from the ideal shape by ~1e-16). The
     stored distance and foot are the numeric ones, exact for the geometry as written; the closed
     form's distance is stored beside them as `closed_form_distance`.

Locations: for curves `interior`, `endpoint` (t at the domain's end) or `kink` (t on an interior knot
of multiplicity = degree where the tangent direction jumps); for surfaces `interior`, `edge`,
`corner` (parameters at the domain's ends) or `kink` (on a knot line of multiplicity = degree across
which the surface's tangent jumps). On a closed curve or surface the domain's ends are marked
`seam: true`; an edge that the net collapses to one point is marked `pole: true` (any parameter
along it gives the foot).

    /usr/bin/python3 tests/tools/gen_nurbs_projection_refs.py           rewrites the file
    /usr/bin/python3 tests/tools/gen_nurbs_projection_refs.py --check   recomputes it and compares
                                                                        (numbers to 1e-30)
"""
import bisect
import json
import math
import os
import random
import sys
from fractions import Fraction as F

import mpmath
from mpmath import mp, mpf

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen_nurbs_refs  # noqa: E402
from gen_nurbs_refs import basis_polynomials, padd, pmul  # noqa: E402

OUT = os.path.join(HERE, "..", "data", "nurbs_projection_cases.json")
mp.dps = 50
SEED = 20261206
DIGITS = 35
R2 = math.sqrt(2.0) / 2.0


# ---- exact pieces ---------------------------------------------------------------------------------
def pshift(a, x0):
    """The polynomial t -> a(t + x0)."""
    out = [F(0)]
    for c in reversed(a):
        out = padd(pmul(out, [x0, F(1)]), [c])
    return out


def breakpoints(U, p, n):
    """Distinct knots of the domain [U_p, U_n], the span index (for basis_polynomials) of each piece
    between them, and the indices (into the distinct knots) of the interior C0 candidates."""
    lo, hi = U[p], U[n]
    distinct = sorted(set(u for u in U if lo <= u <= hi))
    spans = [max(i for i in range(p, n) if U[i] <= a) for a in distinct[:-1]]
    c0 = [k for k, a in enumerate(distinct) if 0 < k < len(distinct) - 1 and U.count(a) >= p]
    return distinct, spans, c0


def local_basis(U, p, n, span):
    """The p + 1 basis functions nonzero on the span, in the local parameter t = u - U_span, each
    as p + 1 coefficients."""
    N = basis_polynomials(U, p, n, span)
    return [(pshift(N[i], U[span]) + [F(0)] * (p + 1))[:p + 1] for i in range(span - p, span + 1)]


class Direction:
    """One parameter direction: knots, degree, the pieces and the cells between C0 knots."""

    def __init__(self, degree, knots, count):
        self.p, self.U, self.n = degree, [F(x) for x in knots], count
        self.breaks, self.spans, c0 = breakpoints(self.U, self.p, self.n)
        self.lo, self.hi = self.breaks[0], self.breaks[-1]
        self.bf = [float(b) for b in self.breaks]
        self.bm = [mpf(b.numerator) / b.denominator for b in self.breaks]
        edges = [0] + c0 + [len(self.breaks) - 1]
        self.cells = [(edges[k], edges[k + 1]) for k in range(len(edges) - 1)]  # break indices
        self.c0 = c0

    def piece(self, x, cell, bounds):
        """The piece (index) holding x inside the cell (break indices a, b); bounds: the breaks as
        numbers of x's kind."""
        a, b = cell
        k = bisect.bisect_right(bounds, x) - 1
        return min(max(k, a), b - 1)

    def grid(self, samples):
        """(value, piece) for a grid of every piece cut into `samples` parts, knots included."""
        out = []
        for k in range(len(self.breaks) - 1):
            a, b = self.breaks[k], self.breaks[k + 1]
            for j in range(samples):
                out.append((float(a + (b - a) * F(j, samples)), k))
        out.append((float(self.hi), len(self.breaks) - 2))
        return out

    def cells_of(self, x):
        """The cells (indices) whose closed box holds x (two at a C0 knot)."""
        return [c for c, (a, b) in enumerate(self.cells) if self.bf[a] <= x <= self.bf[b]]


def to_num(fr, kind):
    return float(fr) if kind is float else mpf(fr.numerator) / fr.denominator


# ---- geometries -----------------------------------------------------------------------------------
class Curve:
    dim = 1

    def __init__(self, d):
        self.d = d
        pts = d["control_points"]
        self.planar = len(pts[0]) == 2
        P = [[F(x) for x in pt] + ([F(0)] if self.planar else []) for pt in pts]
        W = [F(x) for x in d["weights"]] if d.get("weights") else [F(1)] * len(P)
        self.dirs = [Direction(d["degree"], d["knots"], len(P))]
        dr = self.dirs[0]
        self.pieces = {}
        for k, span in enumerate(dr.spans):
            N = local_basis(dr.U, dr.p, dr.n, span)
            idx = range(span - dr.p, span + 1)
            comps = []
            for c in range(3):
                poly = [F(0)]
                for b, i in zip(N, idx):
                    poly = padd(poly, [x * W[i] * P[i][c] for x in b])
                comps.append(poly)
            wpoly = [F(0)]
            for b, i in zip(N, idx):
                wpoly = padd(wpoly, [x * W[i] for x in b])
            comps.append(wpoly)
            self.pieces[k] = comps
        self.closed = P[0] == P[-1] and W[0] == W[-1]
        self.num = {}
        for kind in (float, mpf):
            self.num[kind] = {k: [[to_num(x, kind) for x in poly] for poly in comps] for k, comps in self.pieces.items()}

    def jet(self, x, pieces, kind):
        """S, [S_t], [[S_tt]] at x = (t,) on the given piece index."""
        dr = self.dirs[0]
        k = pieces[0]
        t = x[0] - (dr.bf[k] if kind is float else dr.bm[k])
        vals = []
        for poly in self.num[kind][k]:
            a0 = a1 = a2 = 0
            for c in reversed(poly):  # value and derivatives by Horner
                a2 = a2 * t + 2 * a1
                a1 = a1 * t + a0
                a0 = a0 * t + c
            vals.append((a0, a1, a2))
        w0, w1, w2 = vals[3]
        S, S1, S2 = [], [], []
        for c in range(3):
            a0, a1, a2 = vals[c]
            S.append(a0 / w0)
            S1.append((a1 * w0 - a0 * w1) / w0 ** 2)
            S2.append((a2 * w0 ** 2 - 2 * a1 * w1 * w0 - a0 * w2 * w0 + 2 * a0 * w1 ** 2) / w0 ** 3)
        return S, [S1], [[S2]]

    def point_float(self, t):
        dr = self.dirs[0]
        return self.jet((t,), (dr.piece(t, (0, len(dr.breaks) - 1), dr.bf),), float)[0]


class Surface:
    dim = 2

    def __init__(self, d):
        self.d = d
        net = d["control_points"]
        nu, nv = len(net), len(net[0])
        P = [[[F(x) for x in net[i][j]] for j in range(nv)] for i in range(nu)]
        W = [[F(x) for x in row] for row in d["weights"]] if d.get("weights") else [[F(1)] * nv for _ in range(nu)]
        (p, q) = d["degree"]
        self.dirs = [Direction(p, d["knots"]["u"], nu), Direction(q, d["knots"]["v"], nv)]
        du, dv = self.dirs
        basis_u = {k: local_basis(du.U, p, nu, s) for k, s in enumerate(du.spans)}
        basis_v = {k: local_basis(dv.U, q, nv, s) for k, s in enumerate(dv.spans)}
        self.num = {float: {}, mpf: {}}
        for ku, su in enumerate(du.spans):
            for kv, sv in enumerate(dv.spans):
                comps = [[[F(0)] * (q + 1) for _ in range(p + 1)] for _ in range(4)]
                for a, i in enumerate(range(su - p, su + 1)):
                    for b, j in enumerate(range(sv - q, sv + 1)):
                        Nu, Nv = basis_u[ku][a], basis_v[kv][b]
                        coef = [W[i][j] * P[i][j][c] for c in range(3)] + [W[i][j]]
                        for k in range(p + 1):
                            if Nu[k] == 0:
                                continue
                            for m in range(q + 1):
                                nn = Nu[k] * Nv[m]
                                if nn:
                                    for c in range(4):
                                        comps[c][k][m] += nn * coef[c]
                for kind in (float, mpf):
                    self.num[kind][(ku, kv)] = [[[to_num(x, kind) for x in row] for row in comp] for comp in comps]
        # closed and collapsed edges, from the net
        self.seam = [all(P[0][j] == P[-1][j] and W[0][j] == W[-1][j] for j in range(nv)),
                     all(P[i][0] == P[i][-1] and W[i][0] == W[i][-1] for i in range(nu))]
        self.pole = {(1, 0): all(P[i][0] == P[0][0] for i in range(nu)), (1, 1): all(P[i][-1] == P[0][-1] for i in range(nu)),
                     (0, 0): all(P[0][j] == P[0][0] for j in range(nv)), (0, 1): all(P[-1][j] == P[-1][0] for j in range(nv))}

    def jet(self, x, pieces, kind):
        du, dv = self.dirs
        ku, kv = pieces
        s = x[0] - (du.bf[ku] if kind is float else du.bm[ku])
        t = x[1] - (dv.bf[kv] if kind is float else dv.bm[kv])
        comps = self.num[kind][(ku, kv)]
        p, q = len(comps[0]) - 1, len(comps[0][0]) - 1
        su = [s ** k for k in range(p + 1)]
        su1 = [k * s ** (k - 1) if k else 0 for k in range(p + 1)]
        su2 = [k * (k - 1) * s ** (k - 2) if k > 1 else 0 for k in range(p + 1)]
        tv = [t ** k for k in range(q + 1)]
        tv1 = [k * t ** (k - 1) if k else 0 for k in range(q + 1)]
        tv2 = [k * (k - 1) * t ** (k - 2) if k > 1 else 0 for k in range(q + 1)]
        A = []
        for C in comps:
            r0 = [sum(C[k][m] * tv[m] for m in range(q + 1)) for k in range(p + 1)]
            r1 = [sum(C[k][m] * tv1[m] for m in range(q + 1)) for k in range(p + 1)]
            r2 = [sum(C[k][m] * tv2[m] for m in range(q + 1)) for k in range(p + 1)]
            A.append({(0, 0): sum(a * b for a, b in zip(su, r0)), (1, 0): sum(a * b for a, b in zip(su1, r0)),
                      (2, 0): sum(a * b for a, b in zip(su2, r0)), (0, 1): sum(a * b for a, b in zip(su, r1)),
                      (1, 1): sum(a * b for a, b in zip(su1, r1)), (0, 2): sum(a * b for a, b in zip(su, r2))})
        w = A[3]
        w0 = w[(0, 0)]
        S, Su, Sv, Suu, Suv, Svv = [], [], [], [], [], []
        for c in range(3):
            a = A[c]
            S.append(a[(0, 0)] / w0)
            Su.append((a[(1, 0)] * w0 - a[(0, 0)] * w[(1, 0)]) / w0 ** 2)
            Sv.append((a[(0, 1)] * w0 - a[(0, 0)] * w[(0, 1)]) / w0 ** 2)
            Suu.append((a[(2, 0)] * w0 ** 2 - 2 * a[(1, 0)] * w[(1, 0)] * w0 - a[(0, 0)] * w[(2, 0)] * w0
                        + 2 * a[(0, 0)] * w[(1, 0)] ** 2) / w0 ** 3)
            Svv.append((a[(0, 2)] * w0 ** 2 - 2 * a[(0, 1)] * w[(0, 1)] * w0 - a[(0, 0)] * w[(0, 2)] * w0
                        + 2 * a[(0, 0)] * w[(0, 1)] ** 2) / w0 ** 3)
            Suv.append((a[(1, 1)] * w0 ** 2 - a[(1, 0)] * w[(0, 1)] * w0 - a[(0, 1)] * w[(1, 0)] * w0
                         - a[(0, 0)] * w[(1, 1)] * w0 + 2 * a[(0, 0)] * w[(1, 0)] * w[(0, 1)]) / w0 ** 3)
        return S, [Su, Sv], [[Suu, Suv], [Suv, Svv]]

    def point_float(self, u, v):
        return self.jet_float(u, v)[0]

    def jet_float(self, u, v):
        du, dv = self.dirs
        whole = [(0, len(d.breaks) - 1) for d in self.dirs]
        return self.jet((u, v), (du.piece(u, whole[0], du.bf), dv.piece(v, whole[1], dv.bf)), float)


# ---- the search -----------------------------------------------------------------------------------
def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def fgh(geom, x, cell, p, kind):
    """f = |S - p|^2 / 2, its gradient and Hessian at x, on the pieces of the cell holding x."""
    bounds = [d.bf if kind is float else d.bm for d in geom.dirs]
    pieces = [d.piece(xi, d.cells[c], b) for d, xi, c, b in zip(geom.dirs, x, cell, bounds)]
    S, D1, D2 = geom.jet(x, pieces, kind)
    r = [s - pi for s, pi in zip(S, p)]
    g = [dot(r, D1[k]) for k in range(geom.dim)]
    H = [[dot(D1[k], D1[m]) + dot(r, D2[k][m]) for m in range(geom.dim)] for k in range(geom.dim)]
    return dot(r, r) / 2, g, H, S


def solve(H, g, free):
    """-H_ff^-1 g_f on the free coordinates, or None where H_ff is not positive definite."""
    if len(free) == 1:
        k = free[0]
        return {k: -g[k] / H[k][k]} if H[k][k] > 0 else None
    a, b, c = H[0][0], H[0][1], H[1][1]
    det = a * c - b * b
    if a <= 0 or det <= 0:
        return None
    return {0: -(c * g[0] - b * g[1]) / det, 1: -(a * g[1] - b * g[0]) / det}


def box_of(geom, cell, kind):
    out = []
    for d, c in zip(geom.dirs, cell):
        a, b = d.cells[c]
        bounds = d.bf if kind is float else d.bm
        out.append((bounds[a], bounds[b]))
    return out


def active_set(x, g, box, eps):
    return [k for k in range(len(x)) if (x[k] <= box[k][0] + eps[k] and g[k] > 0) or (x[k] >= box[k][1] - eps[k] and g[k] < 0)]


def descend_float(geom, x, cell, p):
    """Projected Newton with Armijo backtracking over the cell's box, in doubles."""
    box = box_of(geom, cell, float)
    eps = [1e-13 * (b - a) for a, b in box]
    x = [min(max(xi, a), b) for xi, (a, b) in zip(x, box)]
    f, g, H, _ = fgh(geom, x, cell, p, float)
    for _ in range(200):
        act = active_set(x, g, box, eps)
        for k in act:
            x[k] = box[k][0] if g[k] > 0 else box[k][1]
        free = [k for k in range(len(x)) if k not in act]
        if not free:
            break
        step = solve(H, g, free)
        if step is None:  # steepest descent, scaled to a tenth of the box
            norm = math.sqrt(sum(g[k] ** 2 for k in free)) or 1.0
            scale = 0.1 * min(box[k][1] - box[k][0] for k in free)
            step = {k: -g[k] / norm * scale for k in free}
        alpha, moved = 1.0, False
        for _ in range(60):
            y = list(x)
            for k, s in step.items():
                y[k] = min(max(x[k] + alpha * s, box[k][0]), box[k][1])
            fy, gy, Hy, _ = fgh(geom, y, cell, p, float)
            if fy <= f + 1e-4 * sum(g[k] * (y[k] - x[k]) for k in free) or fy <= f and alpha < 1e-6:
                moved = any(abs(y[k] - x[k]) > eps[k] * 1e-3 for k in free)
                x, f, g, H = y, fy, gy, Hy
                break
            alpha /= 2
        if not moved:
            break
    return x


def refine_mp(geom, xf, cell, p):
    """Newton at 50 digits from the double solution on the coordinates not held at a bound; a held
    coordinate whose gradient points into the box is released (active-set iteration)."""
    box = box_of(geom, cell, mpf)
    x = [mpf(v) for v in xf]
    epsf = [1e-11 * (float(b) - float(a)) for a, b in box]
    held = {}
    for k in range(len(x)):
        if abs(xf[k] - float(box[k][0])) <= epsf[k]:
            held[k] = box[k][0]
        elif abs(xf[k] - float(box[k][1])) <= epsf[k]:
            held[k] = box[k][1]
    tiny = mpf(10) ** -44
    for _ in range(4):
        for k, v in held.items():
            x[k] = v
        free = [k for k in range(len(x)) if k not in held]
        for _ in range(60):
            f, g, H, S = fgh(geom, x, cell, p, mpf)
            if not free or max(abs(g[k]) for k in free) < tiny:
                break
            step = solve(H, g, free)
            if step is None:
                break
            for k, s in step.items():
                x[k] = x[k] + s
                if x[k] < box[k][0] or x[k] > box[k][1]:
                    held[k] = x[k] = box[k][0] if x[k] < box[k][0] else box[k][1]
            if any(k in held for k in free) or max(abs(s) for s in step.values()) < mpf(10) ** -42:
                break
        f, g, H, S = fgh(geom, x, cell, p, mpf)
        wrong = [k for k, v in held.items() if (g[k] < -tiny if v == box[k][0] else g[k] > tiny)]
        if not wrong and all(k in held or abs(g[k]) < mpf(10) ** -35 for k in range(len(x))):
            return x, mpmath.sqrt(2 * f), S, True
        for k in wrong:
            del held[k]
    return x, mpmath.sqrt(2 * f), S, False


def grid_minima(values, shape):
    """Indices of the discrete local minima of a grid of values (flattened, row-major)."""
    out = []
    if len(shape) == 1:
        n = shape[0]
        for i in range(n):
            if all(values[i] <= values[j] for j in (i - 1, i + 1) if 0 <= j < n):
                out.append((i,))
        return out
    nu, nv = shape
    for i in range(nu):
        for j in range(nv):
            f = values[i * nv + j]
            ok = True
            for a in (-1, 0, 1):
                for b in (-1, 0, 1):
                    if (a or b) and 0 <= i + a < nu and 0 <= j + b < nv and values[(i + a) * nv + j + b] < f:
                        ok = False
            if ok:
                out.append((i, j))
    return out


class Searcher:
    def __init__(self, geom, samples):
        self.geom = geom
        self.axes = [d.grid(samples) for d in geom.dirs]
        if geom.dim == 1:
            self.nodes = [geom.jet((t,), (k,), float)[0] for t, k in self.axes[0]]
        else:
            self.nodes = [geom.jet((u, v), (ku, kv), float)[0] for u, ku in self.axes[0] for v, kv in self.axes[1]]

    def candidates(self, p):
        """Every refined local minimum of |S - p| (KKT over its cell at 50 digits), nearest first;
        self.unrefined: the least distance of the starts whose refinement did not reach a KKT point."""
        geom = self.geom
        self.unrefined = mpf("inf")
        values = [sum((a - b) ** 2 for a, b in zip(s, p)) for s in self.nodes]
        shape = [len(a) for a in self.axes]
        work = []
        for idx in grid_minima(values, shape):
            x0 = [self.axes[k][idx[k]][0] for k in range(geom.dim)]
            cells = [geom.dirs[k].cells_of(x0[k]) for k in range(geom.dim)]
            work += [(x0, (c,)) for c in cells[0]] if geom.dim == 1 else [(x0, (a, b)) for a in cells[0] for b in cells[1]]
        seen, out = set(), []
        while work:
            x0, cell = work.pop()
            xf = descend_float(geom, list(x0), cell, p)
            key = (cell, tuple(round(v, 9) for v in xf))
            if key in seen:
                continue
            seen.add(key)
            # stopped on a C0 knot line: the neighbouring cell continues from there
            for k, d in enumerate(geom.dirs):
                a, b = d.cells[cell[k]]
                for brk, nxt in ((a, cell[k] - 1), (b, cell[k] + 1)):
                    if 0 <= nxt < len(d.cells) and abs(xf[k] - d.bf[brk]) <= 1e-12 * (d.bf[-1] - d.bf[0]):
                        work.append((list(xf), tuple(nxt if m == k else c for m, c in enumerate(cell))))
            x, dist, S, kkt = refine_mp(geom, xf, cell, p)
            if kkt:
                out.append({"x": x, "cell": cell, "distance": dist, "foot": S})
            else:
                self.unrefined = min(self.unrefined, dist)
        out.sort(key=lambda c: c["distance"])
        return out


# ---- locations ------------------------------------------------------------------------------------
def tangent_jumps(geom, x, k, brk):
    """Whether the derivative along direction k jumps in direction at the C0 knot line x_k = brk."""
    left, right = [], []
    for piece, store in ((brk - 1, left), (brk, right)):
        pieces = []
        for m, dm in enumerate(geom.dirs):
            if m == k:
                pieces.append(piece)
            else:
                pieces.append(dm.piece(x[m], (0, len(dm.breaks) - 1), dm.bm))
        store.append(geom.jet(x, pieces, mpf)[1][k])
    a, b = left[0], right[0]
    na, nb = mpmath.sqrt(dot(a, a)), mpmath.sqrt(dot(b, b))
    if na == 0 or nb == 0:
        return True
    cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    return mpmath.sqrt(dot(cross, cross)) / (na * nb) > mpf(10) ** -10 or dot(a, b) < 0


def describe(geom, c):
    """location and flags. A foot within 1e-14 of the domain's width from an end or a knot is read
    as on it (the doubles the net is written in move the ideal shape's feet by ~1e-16)."""
    x = c["x"]
    ends, flags, kink = [], {}, False
    for k, d in enumerate(geom.dirs):
        tol = mpf(10) ** -14 * (d.bm[-1] - d.bm[0])
        if abs(x[k] - d.bm[0]) < tol or abs(x[k] - d.bm[-1]) < tol:
            ends.append(k)
            end = 0 if abs(x[k] - d.bm[0]) < tol else 1
            if geom.dim == 1 and geom.closed or geom.dim == 2 and geom.seam[k]:
                flags["seam"] = True
            if geom.dim == 2 and geom.pole[(k, end)]:
                flags["pole"] = True
        for brk in range(1, len(d.breaks) - 1):
            if abs(x[k] - d.bm[brk]) < tol:
                flags.setdefault("on_knot", {})["t" if geom.dim == 1 else "uv"[k]] = float(d.breaks[brk])
                if brk in d.c0 and tangent_jumps(geom, x, k, brk):
                    kink = True
    if geom.dim == 1:
        location = "endpoint" if ends else ("kink" if kink else "interior")
    else:
        location = "corner" if len(ends) == 2 else "edge" if ends else ("kink" if kink else "interior")
    return location, flags


def num(x, digits=DIGITS):
    return mpmath.nstr(x, digits, min_fixed=-5, max_fixed=5, strip_zeros=True)


def project(geom, searcher, p, closed_form=None):
    """The reference record of point p (a list of doubles)."""
    pf = [F(x) for x in p] + ([F(0)] if len(p) == 2 else [])
    pm = [mpf(x.numerator) / x.denominator for x in pf]
    cands = searcher.candidates(pm)
    best = cands[0]
    if searcher.unrefined < best["distance"] * (1 - mpf(10) ** -12):
        raise AssertionError("a start that did not refine is nearer (%s) than the best minimum (%s) at %s"
                             % (searcher.unrefined, best["distance"], p))
    rec = {"p": list(p)}
    tie_feet = [c for c in cands[1:] if abs(c["distance"] - best["distance"]) <= mpf(10) ** -30 * max(best["distance"], 1)
                and max(abs(a - b) for a, b in zip(c["foot"], best["foot"])) > mpf(10) ** -12]
    location, flags = describe(geom, best)
    planar = geom.dim == 1 and geom.planar
    foot = best["foot"][:2] if planar else best["foot"]
    rec.update({"distance": float(best["distance"]), "distance_str": num(best["distance"]),
                "params": [float(v) for v in best["x"]], "params_str": [num(v) for v in best["x"]],
                "foot": [float(v) for v in foot], "foot_str": [num(v) for v in foot], "location": location})
    rec.update(flags)
    if tie_feet:
        rec["tie"] = "finite"
        rec["tie_feet"] = [[float(v) for v in (c["foot"][:2] if planar else c["foot"])] for c in tie_feet]
    if "seam" in flags and "pole" not in flags:  # the same foot at the other end of the closed direction
        alls = []
        for c in cands:
            if c["distance"] - best["distance"] <= mpf(10) ** -25 and max(abs(a - b) for a, b in zip(c["foot"], best["foot"])) < mpf(10) ** -14:
                key = [float(v) for v in c["x"]]
                if key not in alls:
                    alls.append(key)
        if len(alls) > 1:
            rec["params_all"] = alls
    if closed_form is not None:
        cf = closed_form(pm)
        rec["closed_form_distance"] = num(cf["distance"])
        if cf.get("continuum"):
            rec.update({"tie": "continuum", "params": None, "params_str": None, "foot": None, "foot_str": None,
                        "location": None})
            for k in ("seam", "pole", "params_all", "tie_feet", "on_knot"):
                rec.pop(k, None)
        else:
            foot_err = max(abs(a - b) for a, b in zip(cf["foot"], best["foot"]))
            if foot_err > 1e-14:
                raise AssertionError("closed form foot differs by %s at %s" % (foot_err, p))
        err = abs(cf["distance"] - best["distance"])
        if err > 1e-14:
            raise AssertionError("closed form distance differs by %s at %s" % (err, p))
        rec["_closed_form_error"] = err
    return rec


# ---- closed forms ---------------------------------------------------------------------------------
def closed_circle(radius):
    def cf(p):
        r = mpmath.sqrt(p[0] ** 2 + p[1] ** 2)
        if r == 0:
            return {"distance": mpf(radius), "continuum": True}
        return {"distance": abs(r - radius), "foot": [radius * p[0] / r, radius * p[1] / r, mpf(0)]}
    return cf


def closed_sphere(p):
    r = mpmath.sqrt(dot(p, p))
    return {"distance": abs(r - 1), "foot": [c / r for c in p]}


def closed_torus(R, r):
    def cf(p):
        rho = mpmath.sqrt(p[0] ** 2 + p[1] ** 2)
        a = [R * p[0] / rho, R * p[1] / rho, mpf(0)]  # the nearest point of the core circle
        e = [pi - ai for pi, ai in zip(p, a)]
        de = mpmath.sqrt(dot(e, e))
        return {"distance": abs(de - r), "foot": [ai + r * ei / de for ai, ei in zip(a, e)]}
    return cf


# ---- the geometries and their points ----------------------------------------------------------------
CIRCLE_SQUARE = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
CIRCLE_WEIGHTS = [1, R2, 1, R2, 1, R2, 1, R2, 1]
CIRCLE_KNOTS = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
HALF_KNOTS = [0, 0, 0, 0.5, 0.5, 1, 1, 1]


def r12(x):
    """A double rounded to 12 significant digits (short points in the file)."""
    return float("%.12g" % x)


def normal_points(geom, rng, count, offset, params=None):
    """Points S(x) + t n(x) with |t| <= offset, x uniform in the inner 90% of the domain (or given)."""
    out = []
    dirs = geom.dirs
    while len(out) < count:
        if params is not None:
            x = params[len(out)]
        else:
            x = [float(d.lo) + float(d.hi - d.lo) * (0.05 + 0.9 * rng.random()) for d in dirs]
        if geom.dim == 1:
            S, D1, _ = geom.jet((x[0],), (dirs[0].piece(x[0], (0, len(dirs[0].breaks) - 1), dirs[0].bf),), float)
            tng = D1[0]
            if geom.planar:
                n = [-tng[1], tng[0], 0.0]
            else:
                ax = [rng.gauss(0, 1) for _ in range(3)]
                tt = dot(tng, tng)
                n = [a - dot(ax, tng) / tt * b for a, b in zip(ax, tng)]
        else:
            S, D1, _ = geom.jet_float(*x)
            a, b = D1
            n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        ln = math.sqrt(dot(n, n))
        if ln < 1e-9:
            continue
        t = offset * (2 * rng.random() - 1)
        q = [s + t * c / ln for s, c in zip(S, n)]
        if params is None:  # short numbers; a foot meant on a knot keeps the full double
            q = [r12(c) for c in q]
        out.append(q[:2] if geom.dim == 1 and geom.planar else q)
    return out


def uniform_points(rng, box, count, planar=False):
    pts = [[r12(a + (b - a) * rng.random()) for a, b in box] for _ in range(count)]
    return [q[:2] for q in pts] if planar else pts


def definitions():
    """Every geometry: (name, definition, closed form or None, point generator)."""
    rng = random.Random(SEED)
    out = []

    circle = {"type": "bspline_curve", "degree": 2, "knots": CIRCLE_KNOTS,
              "control_points": [[2.0 * a, 2.0 * b] for a, b in CIRCLE_SQUARE], "weights": CIRCLE_WEIGHTS}

    def circle_points(g):
        pts = [[0.0, 0.0], [3.0, 0.0], [1.0, 0.0], [0.0, 2.5], [-1.2, 0.0], [0.0, -0.01], [2.01, 0.0],
               [1.99, -1e-9], [5.0, 5.0], [-0.3, 0.4], [1.41, 1.42], [100.0, -37.0], [2.0, 0.0]]
        pts += normal_points(g, rng, 8, 0.04)
        pts += [[r12(r * math.cos(a)), r12(r * math.sin(a))] for r, a in ((0.5, 2.0), (7.0, -2.5), (1.5, 4.0), (2.5, 0.7))]
        return pts
    out.append(("nurbs circle r=2", circle, closed_circle(2), circle_points))

    planar = {"type": "bspline_curve", "degree": 3, "knots": [0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1],
              "control_points": [[0, 0], [1, 2], [2, -1], [3, 2.5], [4, 0], [5, 1.5], [6, -0.5]]}

    def planar_points(g):
        pts = [[-1.0, -0.5], [-0.5, 1.0], [7.0, -1.0], [6.5, 0.5], [3.0, 10.0], [3.0, -6.0], [50.0, 20.0]]
        pts += normal_points(g, rng, 10, 0.06)
        pts += normal_points(g, rng, 3, 0.06, params=[[0.25], [0.5], [0.75]])  # feet on knots
        pts += uniform_points(rng, [(-1, 7), (-2, 3)], 6, planar=True)
        return pts
    out.append(("planar cubic, clamped uniform", planar, None, planar_points))

    cps = [[r12(i * 0.8 + rng.uniform(-0.3, 0.3)), r12(rng.uniform(-1.5, 1.5)), r12(rng.uniform(-1.5, 1.5))] for i in range(8)]
    space = {"type": "bspline_curve", "degree": 3, "knots": [0, 0, 0, 0, 0.7, 1.6, 1.6, 1.6, 3, 3, 3, 3],
             "control_points": cps}

    def space_points(g):
        # in the kink's normal cone: K + s (tl/|tl| - tr/|tr|) + e b, tl and tr the one-sided tangents
        dr = g.dirs[0]
        K, (tl,), _ = g.jet((1.6,), (dr.cells[0][1] - 1,), float)
        tr = g.jet((1.6,), (dr.cells[1][0],), float)[1][0]
        tl = [c / math.sqrt(dot(tl, tl)) for c in tl]
        tr = [c / math.sqrt(dot(tr, tr)) for c in tr]
        cone = [a - b for a, b in zip(tl, tr)]
        b = [tl[1] * tr[2] - tl[2] * tr[1], tl[2] * tr[0] - tl[0] * tr[2], tl[0] * tr[1] - tl[1] * tr[0]]
        b = [c / math.sqrt(dot(b, b)) for c in b]
        pts = [[r12(k + s * c + e * d) for k, c, d in zip(K, cone, b)]
               for s, e in ((0.02, 0.0), (0.1, 0.03), (0.3, -0.1), (0.05, 0.4), (1e-4, 1e-5))]
        pts += [[-2.0, 0.0, 0.0], [8.0, 1.0, -1.0], [3.0, 10.0, 2.0], [2.5, -0.2, 7.0]]
        pts += normal_points(g, rng, 10, 0.06)
        pts += uniform_points(rng, [(-1, 7), (-2.5, 2.5), (-2.5, 2.5)], 5)
        return pts
    out.append(("space cubic, triple knot (C0 kink) at 1.6", space, None, space_points))

    # bicubic, 8 x 8 patches over [0,4]^2
    knots8 = [0, 0, 0, 0] + [0.5 * k for k in range(1, 8)] + [4, 4, 4, 4]
    net = [[[0.4 * i, 0.4 * j, round((0.3 * math.sin(1.3 * 0.4 * i + 0.7 * 0.4 * j) + rng.uniform(-0.05, 0.05)) * 1024) / 1024]
            for j in range(11)] for i in range(11)]
    b8 = {"type": "bspline_surface", "degree": [3, 3], "knots": {"u": knots8, "v": knots8}, "control_points": net}

    def b8_points(g):
        pts = normal_points(g, rng, 8, 0.05)
        pts += normal_points(g, rng, 4, 0.05, params=[[1.5, 2.3], [0.7, 2.0], [3.0, 3.5], [2.5, 0.5]])
        pts += [[-0.5, 1.7, 0.2], [4.6, 2.2, -0.3], [1.1, -0.8, 0.5], [2.9, 4.4, 1.0],  # beyond edges
                [-0.6, -0.7, 0.1], [4.5, 4.3, -0.5], [-0.4, 4.9, 0.0], [4.8, -0.2, 0.9],  # beyond corners
                [2.0, 2.0, 3.0], [1.0, 3.0, -2.0], [30.0, -10.0, 5.0]]
        pts += uniform_points(rng, [(-4, 8), (-4, 8), (-2, 2)], 5)
        return pts
    out.append(("bicubic 8 x 8 patches", b8, None, b8_points))

    # the rational sphere: u around the z axis (the circle), v from the south pole to the north pole
    prof = [(0, -1), (1, -1), (1, 0), (1, 1), (0, 1)]
    wv = [1, R2, 1, R2, 1]
    sphere = {"type": "bspline_surface", "degree": [2, 2], "knots": {"u": CIRCLE_KNOTS, "v": HALF_KNOTS},
              "control_points": [[[a * r, b * r, z] for r, z in prof] for a, b in CIRCLE_SQUARE],
              "weights": [[wu * w if (wu, w) != (R2, R2) else 0.5 for w in wv] for wu in CIRCLE_WEIGHTS]}

    def sphere_points(g):
        pts = [[0.0, 0.0, 2.0], [0.0, 0.0, -0.5], [0.0, 0.0, 1.001], [1e-3, 2e-3, 0.9],  # the poles
               [1.5, 0.0, 0.3], [0.4, 0.0, -0.2], [1.0, -1e-12, 0.0],  # the seam u = 0 (y = 0, x > 0)
               [0.0, 1.2, 0.0], [-0.7, -0.7, 0.2], [3.0, -4.0, 12.0], [0.2, 0.1, -0.1]]
        pts += normal_points(g, rng, 8, 0.02)
        pts += uniform_points(rng, [(-2, 2)] * 3, 6)
        return pts
    out.append(("rational sphere r=1", sphere, closed_sphere, sphere_points))

    tprof = [(2 + 0.5 * a, 0.5 * b) for a, b in CIRCLE_SQUARE]
    torus = {"type": "bspline_surface", "degree": [2, 2], "knots": {"u": CIRCLE_KNOTS, "v": CIRCLE_KNOTS},
             "control_points": [[[a * r, b * r, z] for r, z in tprof] for a, b in CIRCLE_SQUARE],
             "weights": [[wu * w if (wu, w) != (R2, R2) else 0.5 for w in CIRCLE_WEIGHTS] for wu in CIRCLE_WEIGHTS]}

    def torus_points(g):
        pts = [[3.0, 0.0, 0.0], [2.6, 0.0, 0.1], [0.5, 0.0, 0.0], [2.0, 0.0, 0.2], [0.0, 2.3, 0.05],
               [-1.0, -1.2, 0.8], [0.3, 0.4, 2.0], [5.0, 5.0, -1.0], [1.7, -0.9, -0.3], [0.9, 0.0, -0.4]]
        pts += normal_points(g, rng, 8, 0.03)
        pts += uniform_points(rng, [(-3, 3), (-3, 3), (-1, 1)], 6)
        return pts
    out.append(("torus R=2 r=0.5", torus, closed_torus(2, 0.5), torus_points))

    # a biquadratic ridge: u knot 1 of multiplicity 2 = degree, the surface folds along u = 1
    fold = {"type": "bspline_surface", "degree": [2, 2], "knots": {"u": [0, 0, 0, 1, 1, 2, 2, 2], "v": [0, 0, 0, 1, 1, 1]},
            "control_points": [[[x, y, z + (0.25 if j == 1 else 0.0)] for j, y in enumerate((0.0, 1.0, 2.0))]
                               for x, z in ((0.0, 0.0), (0.5, 0.6), (1.0, 1.0), (1.6, 0.5), (2.0, 0.0))]}

    def fold_points(g):
        ridge = [g.point_float(1.0, v) for v in (0.2, 0.5, 0.8)]
        pts = [[r12(q[0] + dx), r12(q[1]), r12(q[2] + dz)] for q, (dx, dz) in zip(ridge * 2, ((0.02, 0.5), (-0.05, 0.3), (0.1, 1.0),
                                                                                            (0.0, 0.05), (0.03, 2.0), (-0.1, 0.8)))]
        pts += [[-0.5, 1.0, 0.2], [2.5, 0.7, -0.2], [1.0, -0.6, 1.5], [1.2, 2.7, 0.9], [-0.3, -0.4, -0.1],
                [2.4, 2.3, 0.2], [1.0, 1.0, -3.0]]
        pts += normal_points(g, rng, 8, 0.03)
        pts += uniform_points(rng, [(-2, 4), (-2, 4), (-1, 2)], 4)
        return pts
    out.append(("biquadratic ridge, C0 fold at u = 1", fold, None, fold_points))

    # random rational, unclamped non-uniform knots (verb / ANurbs-style test data); a stream of
    # their own, so that the geometries above keep their points
    rr = random.Random(SEED + 1)

    def unclamped(count, degree):
        knots = [0.0]
        for _ in range(count + degree):
            knots.append(knots[-1] + rr.choice((0.25, 0.5, 0.75, 1.0)))
        return knots

    rcurve = {"type": "bspline_curve", "degree": 4, "knots": unclamped(9, 4),
              "control_points": [[r12(0.7 * i + rr.uniform(-0.4, 0.4)), r12(rr.uniform(-1.5, 1.5)), r12(rr.uniform(-1.5, 1.5))]
                                 for i in range(9)],
              "weights": [r12(rr.uniform(0.5, 2.0)) for _ in range(9)]}

    def rcurve_points(g):
        pts = normal_points(g, rr, 10, 0.05)
        ends = [g.point_float(float(g.dirs[0].lo)), g.point_float(float(g.dirs[0].hi))]
        pts += [[r12(c + d) for c, d in zip(e, off)] for e in ends for off in ((-0.6, 0.2, 0.1), (0.5, -0.3, 0.4))]
        pts += uniform_points(rr, [(-1, 7), (-2.5, 2.5), (-2.5, 2.5)], 8)
        return pts
    out.append(("random rational quartic, unclamped", rcurve, None, rcurve_points))

    rsurf = {"type": "bspline_surface", "degree": [3, 2], "knots": {"u": unclamped(7, 3), "v": unclamped(6, 2)},
             "control_points": [[[r12(0.6 * i + rr.uniform(-0.15, 0.15)), r12(0.6 * j + rr.uniform(-0.15, 0.15)),
                                  r12(rr.uniform(-0.6, 0.6))] for j in range(6)] for i in range(7)],
             "weights": [[r12(rr.uniform(0.5, 2.0)) for _ in range(6)] for _ in range(7)]}

    def rsurf_points(g):
        pts = normal_points(g, rr, 10, 0.04)
        (u0, u1), (v0, v1) = [(float(d.lo), float(d.hi)) for d in g.dirs]
        for a, b in ((u0, (v0 + v1) / 2), (u1, (v0 + v1) / 3), ((u0 + u1) / 2, v0), (u0, v1), (u1, v0)):
            S, (su, sv), _ = g.jet_float(a, b)
            out_u = -1 if a == u0 else 1 if a == u1 else 0
            out_v = -1 if b == v0 else 1 if b == v1 else 0
            pts.append([r12(c + 0.3 * (out_u * x / math.sqrt(dot(su, su)) + out_v * y / math.sqrt(dot(sv, sv))) + (0.2 if k == 2 else 0))
                        for k, (c, x, y) in enumerate(zip(S, su, sv))])
        pts += uniform_points(rr, [(-1, 4.5), (-1, 4), (-1.5, 1.5)], 8)
        return pts
    out.append(("random rational (3, 2), unclamped", rsurf, None, rsurf_points))
    return out


def build(definition):
    return Curve(definition) if definition["type"] == "bspline_curve" else Surface(definition)


SAMPLES = {"bspline_curve": 24, "bspline_surface": 8}


def check_evaluation(geom, definition, rng):
    """The pieces against tests/tools/gen_nurbs_refs.py's exact evaluation (the basis polynomials in
    the global parameter, the quotient rule on Fractions) at a few parameters: point and first
    derivatives to 1e-40."""
    case = dict(definition)
    case.setdefault("weights", [])
    for _ in range(4):
        x = [float(d.lo) + float(d.hi - d.lo) * rng.random() for d in geom.dirs]
        pieces = [d.piece(mpf(xi), (0, len(d.breaks) - 1), d.bm) for d, xi in zip(geom.dirs, x)]
        S, D1, _ = geom.jet([mpf(xi) for xi in x], pieces, mpf)
        if geom.dim == 1:
            c0, c1, _ = gen_nurbs_refs.curve_point(case, x[0])
            exact = [c0, c1]
        else:
            s, su, sv = gen_nurbs_refs.surface_point(case, x[0], x[1])[:3]
            exact = [s, su, sv]
        for mine, ref in zip([S] + D1, exact):
            err = max(abs(a - (mpf(b.numerator) / b.denominator)) for a, b in zip(mine, ref))
            if err > mpf(10) ** -40:
                raise AssertionError("evaluation differs from gen_nurbs_refs by %s at %s" % (err, x))


def generate(log=True):
    out = {"about": ABOUT, "generated_by": "tests/tools/gen_nurbs_projection_refs.py (seed %d)" % SEED, "cases": []}
    worst = 0.0
    for name, definition, closed_form, points in definitions():
        geom = build(definition)
        check_evaluation(geom, definition, random.Random(SEED + len(out["cases"])))
        searcher = Searcher(geom, SAMPLES[definition["type"]])
        recs = []
        for p in points(geom):
            r = project(geom, searcher, p, closed_form)
            if "_closed_form_error" in r:
                worst = max(worst, float(r.pop("_closed_form_error")))
            recs.append(r)
        out["cases"].append({"name": name, "definition": definition, "points": recs})
        if log:
            print("gen_nurbs_projection_refs: %s: %d points (%s)" % (
                name, len(recs), ", ".join("%s %d" % (k, sum(1 for r in recs if r["location"] == k))
                                          for k in ("interior", "edge", "corner", "endpoint", "kink", None)
                                          if any(r["location"] == k for r in recs))), flush=True)
    if log:
        print("gen_nurbs_projection_refs: closed forms agree to %.1e" % worst)
    return out


ABOUT = ("Global nearest points on NURBS curves and surfaces (issue 35's bspline_curve and bspline_surface "
         "definitions, exactly as POST /v1/geometries takes them), by tests/tools/gen_nurbs_projection_refs.py (its "
         "header: exact per-span polynomial pieces from the Cox-de Boor recurrence in rational arithmetic; a dense grid "
         "over every knot span as the start set; projected Newton over the cells between C0 knots in doubles, then "
         "Newton at 50 digits (mpmath) on every local minimum: interior grad = 0, edges 1-D, corners; the smallest "
         "kept). Circle, sphere and torus: the closed-form distance of the ideal shape (closed_form_distance) agrees "
         "with the numeric one to 1e-14; the stored distance, foot and parameters are the numeric ones, exact for the "
         "geometry as written (its sqrt(2)/2 weights are doubles). distance_str, params_str, foot_str: 35 digits. "
         "location: interior | endpoint | kink (curves), interior | edge | corner | kink (surfaces); seam: the foot is "
         "at the end of a closed direction (params_all lists both ends); pole: an edge the net collapses to a point "
         "(any parameter along it gives the foot); on_knot: the interior knot (line) the foot is on (within 1e-14 "
         "of the domain's width, as for ends), a kink if its multiplicity = degree and the tangent jumps there. "
         "tie 'continuum': every point of the curve is nearest (the circle's centre; params, foot, location null).")


# ---- check ----------------------------------------------------------------------------------------
def compare(a, b, path, errors):
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            errors.append("%s: keys %s vs %s" % (path, sorted(a), sorted(b)))
        for k in set(a) & set(b):
            compare(a[k], b[k], path + "." + k, errors)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            errors.append("%s: length %d vs %d" % (path, len(a), len(b)))
        for i, (x, y) in enumerate(zip(a, b)):
            compare(x, y, "%s[%d]" % (path, i), errors)
    elif a is None or b is None:
        if a is not b:
            errors.append("%s: %r vs %r" % (path, a, b))
    elif path.endswith("_str") or "_str[" in path or path.endswith("closed_form_distance"):
        x, y = mpf(a), mpf(b)
        if abs(x - y) > mpf(10) ** -30 * max(1, abs(x)):
            errors.append("%s: %s vs %s" % (path, a, b))
    elif isinstance(a, float) and isinstance(b, float):
        if abs(a - b) > 1e-15 * max(1.0, abs(a)):
            errors.append("%s: %r vs %r" % (path, a, b))
    elif a != b:
        errors.append("%s: %r vs %r" % (path, a, b))


def main():
    data = generate(log="--quiet" not in sys.argv)
    if "--check" in sys.argv:
        with open(OUT, encoding="utf-8") as f:
            stored = json.load(f)
        errors = []
        compare(stored, json.loads(json.dumps(data)), "", errors)
        for e in errors[:20]:
            print("gen_nurbs_projection_refs: differs: " + e)
        if errors:
            print("gen_nurbs_projection_refs: %d differences from tests/data/nurbs_projection_cases.json" % len(errors))
            return 1
        n = sum(len(c["points"]) for c in stored["cases"])
        print("gen_nurbs_projection_refs: the %d stored references are what the generator computes" % n)
        return 0
    with open(OUT, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
    print("gen_nurbs_projection_refs: wrote " + os.path.relpath(OUT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
