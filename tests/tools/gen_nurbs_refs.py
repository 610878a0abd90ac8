#!/usr/bin/python3
"""Reference values for tests/core/parametric/geometry/nurbs_test.cpp: points of NURBS curves and surfaces and their
derivatives to second order, in exact rational arithmetic (Python's fractions), by a method of
its own: on the knot span of the parameter every basis function N_{i,p} is a polynomial, built
as one from the Cox-de Boor recurrence

    N_{i,0} = 1 on [U_i, U_{i+1}), else 0
    N_{i,p}(u) = (u - U_i) / (U_{i+p} - U_i) N_{i,p-1}(u) + (U_{i+p+1} - u) / (U_{i+p+1} - U_{i+1}) N_{i+1,p-1}(u)

(0/0 read as 0) with polynomial arithmetic, then differentiated exactly; the rational point
C = A / w and its derivatives by the quotient rule written out (C' = (A'w - Aw') / w^2, ...), not
by the recursive Leibniz formula the C++ code uses. The span of an interior knot is the one on its
right; at the domain's upper end the last non-empty span (the convention of the C++ code's
find_span, part of the definition being tested). Every input is a binary double, read exactly.

    /usr/bin/python3 tests/tools/gen_nurbs_refs.py           rewrites tests/data/geometry_nurbs_refs.json
    /usr/bin/python3 tests/tools/gen_nurbs_refs.py --check   recomputes it and compares (ctest)
"""
import json
import math
import os
import random
import sys
from fractions import Fraction as F

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "data", "geometry_nurbs_refs.json")


# ---- polynomials as coefficient lists, lowest degree first, Fraction coefficients ----------------
def padd(a, b):
    n = max(len(a), len(b))
    return [(a[i] if i < len(a) else F(0)) + (b[i] if i < len(b) else F(0)) for i in range(n)]


def pmul(a, b):
    out = [F(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def pder(a):
    return [i * a[i] for i in range(1, len(a))] or [F(0)]


def peval(a, x):
    s = F(0)
    for c in reversed(a):
        s = s * x + c
    return s


def span_of(U, p, n, u):
    """The span index i (p <= i <= n - 1) the C++ find_span picks."""
    if u >= U[n]:
        i = n - 1
        while i > p and not U[i] < U[i + 1]:
            i -= 1
        return i
    if u <= U[p]:
        i = p
        while i < n - 1 and not U[i] < U[i + 1]:
            i += 1
        return i
    return max(i for i in range(p, n) if U[i] <= u)


def basis_polynomials(U, p, n, span):
    """N_{i,p} for i = 0..n-1 as polynomials valid on [U_span, U_span+1]."""
    N = [[F(1)] if i == span else [F(0)] for i in range(len(U) - 1)]
    for k in range(1, p + 1):
        nxt = []
        for i in range(len(U) - 1 - k):
            term = [F(0)]
            d1 = U[i + k] - U[i]
            if d1 != 0:
                term = padd(term, pmul([-U[i] / d1, F(1) / d1], N[i]))
            d2 = U[i + k + 1] - U[i + 1]
            if d2 != 0:
                term = padd(term, pmul([U[i + k + 1] / d2, F(-1) / d2], N[i + 1]))
            nxt.append(term)
        N = nxt
    return N[:n]


def derivs(poly, x):
    return [peval(poly, x), peval(pder(poly), x), peval(pder(pder(poly)), x)]


def rational(A, w):
    """value, first and second derivative of A / w along one parameter (A vectors, w scalars:
    each [f, f', f''])."""
    a0, a1, a2 = A
    w0, w1, w2 = w
    c0 = [x / w0 for x in a0]
    c1 = [(a1[k] * w0 - a0[k] * w1) / w0**2 for k in range(3)]
    c2 = [(a2[k] * w0**2 - 2 * a1[k] * w1 * w0 - a0[k] * w2 * w0 + 2 * a0[k] * w1**2) / w0**3 for k in range(3)]
    return c0, c1, c2


def curve_point(case, t):
    p, U = case["degree"], [F(x) for x in case["knots"]]
    P = [[F(x) for x in pt] + ([F(0)] if len(pt) == 2 else []) for pt in case["control_points"]]
    W = [F(x) for x in case["weights"]] if case["weights"] else [F(1)] * len(P)
    n, u = len(P), F(t)
    N = basis_polynomials(U, p, n, span_of(U, p, n, u))
    d = [derivs(Ni, u) for Ni in N]
    A = [[sum(d[i][k] * W[i] * P[i][c] for i in range(n)) for c in range(3)] for k in range(3)]
    w = [sum(d[i][k] * W[i] for i in range(n)) for k in range(3)]
    return rational(A, w)


def surface_point(case, u, v):
    (p, q), Uu, Uv = case["degree"], [F(x) for x in case["knots"]["u"]], [F(x) for x in case["knots"]["v"]]
    net = case["control_points"]
    nu, nv = len(net), len(net[0])
    P = [[[F(x) for x in net[i][j]] for j in range(nv)] for i in range(nu)]
    W = [[F(x) for x in row] for row in case["weights"]] if case["weights"] else [[F(1)] * nv for _ in range(nu)]
    u, v = F(u), F(v)
    Nu = [derivs(b, u) for b in basis_polynomials(Uu, p, nu, span_of(Uu, p, nu, u))]
    Nv = [derivs(b, v) for b in basis_polynomials(Uv, q, nv, span_of(Uv, q, nv, v))]

    def A(k, l):  # ∂^k_u ∂^l_v of (Σ N_i M_j w_ij P_ij, Σ N_i M_j w_ij)
        vec = [sum(Nu[i][k] * Nv[j][l] * W[i][j] * P[i][j][c] for i in range(nu) for j in range(nv)) for c in range(3)]
        w = sum(Nu[i][k] * Nv[j][l] * W[i][j] for i in range(nu) for j in range(nv))
        return vec, w

    a00, w00 = A(0, 0)
    a10, w10 = A(1, 0)
    a01, w01 = A(0, 1)
    a20, w20 = A(2, 0)
    a02, w02 = A(0, 2)
    a11, w11 = A(1, 1)
    s = [x / w00 for x in a00]
    su = [(a10[k] * w00 - a00[k] * w10) / w00**2 for k in range(3)]
    sv = [(a01[k] * w00 - a00[k] * w01) / w00**2 for k in range(3)]
    suu = [(a20[k] * w00**2 - 2 * a10[k] * w10 * w00 - a00[k] * w20 * w00 + 2 * a00[k] * w10**2) / w00**3 for k in range(3)]
    svv = [(a02[k] * w00**2 - 2 * a01[k] * w01 * w00 - a00[k] * w02 * w00 + 2 * a00[k] * w01**2) / w00**3 for k in range(3)]
    suv = [(a11[k] * w00**2 - a10[k] * w01 * w00 - a01[k] * w10 * w00 - a00[k] * w11 * w00 + 2 * a00[k] * w10 * w01)
           / w00**3 for k in range(3)]
    return s, su, sv, suu, suv, svv


def text(x):
    """A Fraction to 25 significant digits."""
    if x == 0:
        return "0"
    e = math.floor(math.log10(abs(float(x)))) if float(x) != 0 else 0
    scaled = round(x * F(10) ** (24 - e))
    return f"{scaled}e{e - 24}"


def cases():
    rng = random.Random(20261206)
    r2 = math.sqrt(2.0) / 2.0
    curves = [
        {"name": "circle (9 points, quarter arcs)", "degree": 2,
         "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
         "control_points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
         "weights": [1, r2, 1, r2, 1, r2, 1, r2, 1],
         "params": [0, 0.1, 0.25, 0.3, 0.5, 0.875, 1]},
        {"name": "cubic with a double interior knot", "degree": 3,
         "knots": [0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3],
         "control_points": [[0, 0, 0], [1, 2, 0], [2, -1, 1], [3, 3, 2], [4, 0, -1], [5, 1, 0], [6, 2, 1]],
         "weights": [], "params": [0, 0.5, 1, 1.7, 2, 2.25, 3]},
        {"name": "polyline", "degree": 1, "knots": [0, 0, 1, 2.5, 3, 3],
         "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 1], [3, 1, 1]], "weights": [], "params": [0, 0.5, 1, 2, 3]},
    ]
    n, p = 8, 4  # a random rational quartic on an unclamped knot vector
    knots = sorted(rng.randint(0, 40) / 8 for _ in range(n + p + 1))
    knots[p + 1] = knots[p] + 0.5  # a non-empty first span
    knots = sorted(knots)
    curves.append({"name": "random rational quartic, unclamped", "degree": p, "knots": knots,
                   "control_points": [[rng.randint(-16, 16) / 4 for _ in range(3)] for _ in range(n)],
                   "weights": [rng.randint(1, 16) / 4 for _ in range(n)],
                   "params": [knots[p], (knots[p] + knots[n]) / 2, knots[p + 1], knots[n] - 0.125, knots[n]]})
    surfaces = [
        {"name": "bicubic 5 x 6 with a double knot in v", "degree": [3, 3],
         "knots": {"u": [0, 0, 0, 0, 0.5, 1, 1, 1, 1], "v": [0, 0, 0, 0, 1, 1, 2, 2, 2, 2]},
         "control_points": [[[i, j, ((i * 7 + j * 3) % 5) / 2 - 1] for j in range(6)] for i in range(5)],
         "weights": [], "params": [[0, 0], [0.25, 0.5], [0.5, 1], [0.75, 1.5], [1, 2], [0.1, 1.9]]},
        {"name": "rational biquadratic octant of the unit sphere", "degree": [2, 2],
         "knots": {"u": [0, 0, 0, 1, 1, 1], "v": [0, 0, 0, 1, 1, 1]},
         "control_points": [[[1, 0, 0], [1, 0, 1], [0, 0, 1]], [[1, 1, 0], [1, 1, 1], [0, 0, 1]],
                            [[0, 1, 0], [0, 1, 1], [0, 0, 1]]],
         "weights": [[1, r2, 1], [r2, 0.5, r2], [1, r2, 1]],
         "params": [[0, 0], [0.5, 0.5], [0.3, 0.8], [1, 0.25], [1, 1]]},
    ]
    nu, nv, pu, pv = 6, 5, 3, 2
    ku = sorted(rng.randint(0, 24) / 4 for _ in range(nu + pu + 1))
    kv = sorted(rng.randint(0, 24) / 4 for _ in range(nv + pv + 1))
    ku[pu + 1] = max(ku[pu + 1], ku[pu] + 0.25)
    kv[pv + 1] = max(kv[pv + 1], kv[pv] + 0.25)
    ku, kv = sorted(ku), sorted(kv)
    surfaces.append({"name": "random rational (3, 2), unclamped", "degree": [pu, pv], "knots": {"u": ku, "v": kv},
                     "control_points": [[[rng.randint(-8, 8) / 2 for _ in range(3)] for _ in range(nv)] for _ in range(nu)],
                     "weights": [[rng.randint(1, 12) / 4 for _ in range(nv)] for _ in range(nu)],
                     "params": [[ku[pu], kv[pv]], [(ku[pu] + ku[nu]) / 2, (kv[pv] + kv[nv]) / 2],
                                [ku[pu + 1], kv[nv] - 0.125], [ku[nu], kv[nv]]]})
    return curves, surfaces


def generate():
    curves, surfaces = cases()
    out = {"about": "tests/tools/gen_nurbs_refs.py: exact rational references, 25 digits", "curves": [], "surfaces": []}
    for c in curves:
        entry = {k: c[k] for k in ("name", "degree", "knots", "control_points", "weights")}
        entry["points"] = []
        for t in c["params"]:
            c0, c1, c2 = curve_point(c, t)
            entry["points"].append({"t": t, "c": [text(x) for x in c0], "d1": [text(x) for x in c1],
                                    "d2": [text(x) for x in c2]})
        out["curves"].append(entry)
    for s in surfaces:
        entry = {k: s[k] for k in ("name", "degree", "knots", "control_points", "weights")}
        entry["points"] = []
        for u, v in s["params"]:
            jet = surface_point(s, u, v)
            names = ("s", "su", "sv", "suu", "suv", "svv")
            point = {"u": u, "v": v}
            point.update({name: [text(x) for x in value] for name, value in zip(names, jet)})
            entry["points"].append(point)
        out["surfaces"].append(entry)
    return json.dumps(out, indent=1) + "\n"


def main():
    data = generate()
    if "--check" in sys.argv:
        with open(OUT, encoding="utf-8") as f:
            if f.read() != data:
                print("gen_nurbs_refs: tests/data/geometry_nurbs_refs.json differs from what the generator computes")
                return 1
        print("gen_nurbs_refs: the references are what the generator computes")
        return 0
    with open(OUT, "w", encoding="utf-8") as f:
        f.write(data)
    print(f"gen_nurbs_refs: wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
