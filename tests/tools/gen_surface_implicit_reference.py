#!/usr/bin/python3
"""Reference nearest points on implicit surfaces f(x, y, z) = 0 clipped to a box, to 50 digits.

Writes tests/data/surface_implicit_cases.json (or checks it: `check FILE`). Independent of
footpoint's C++ code: sympy for f and its exact derivatives, scipy's brentq on dense lines for the
samples, mpmath at 50 digits for the polishing. For each point p the global nearest point of
S = {f = 0} ∩ B is the nearest of these candidates, each a point of S ∩ B:
  interior   the Lagrange system x - p + l grad f(x) = 0, f(x) = 0 solved by mpmath's Newton from
             the nearest samples and every sample nearer than its neighbours within 3 h (samples:
             where f changes sign along lines parallel to each axis through an n x n grid of the
             box, h the grid's spacing), kept when it converges inside B;
  box-face   the same with one coordinate fixed at a bound (the curve where S meets a face), from
             the samples on that face's lines;
  box-edge   the sign changes of f along each of the 12 edges, polished by mpmath's findroot;
  box-corner a corner where f = 0 exactly (in exact rational arithmetic);
  singular   grad f = 0 and f = 0 (mpmath's Newton on grad f = 0 from the grid nodes where |grad f| is
             smallest), kept inside B.
Every critical point found is a point of S, so the nearest candidate is at most the global
distance; the samples are points of S too and none may be nearer than the answer (checked; a
failure means the sampling missed a piece).
Usage: gen_surface_implicit_reference.py [--lines N] [--out FILE]   (all cases)
       gen_surface_implicit_reference.py check FILE [--lines N]     ("N passed, M failed")
Run with Debian's python3-numpy, python3-scipy, python3-sympy, python3-mpmath.
"""
import argparse
import itertools
import json
import sys

import mpmath
import numpy as np
import sympy
from scipy.optimize import brentq
from scipy.spatial import cKDTree

mpmath.mp.dps = 50
X, Y, Z = sympy.symbols("x y z")

CASES = [
    {"id": "sphere", "f": "x^2+y^2+z^2-1", "box": [[-2, 2], [-2, 2], [-2, 2]],
     "points": [[5, 3, 2], [0.3, 0.2, 0.1], [0.6, 0.8, 0], [0, 0, 3], [-1.5, 0.25, 1.75], [40, -30, 20]]},
    {"id": "ellipsoid", "f": "x^2/4+y^2+4*z^2-1", "box": [[-3, 3], [-3, 3], [-3, 3]],
     "points": [[3, 1, 1], [0.5, 0.1, 0.05], [1.2, 0.3, -0.2], [0, 0, 2], [-2.5, -1.5, 0.4], [1.9, 0.2, 0.1]]},
    {"id": "torus", "f": "(x^2+y^2+z^2+3.75)^2-16*(x^2+y^2)", "box": [[-3, 3], [-3, 3], [-1, 1]],
     "points": [[3, 0.5, 0.2], [0.5, 0.3, 0.1], [2.1, 0.1, 0.05], [0.1, 0.05, 0.9], [-1.2, 1.9, -0.3],
                [2.9, -0.4, 0.95]]},
    {"id": "cone", "f": "x^2+y^2-z^2", "box": [[-1, 1], [-1, 1], [0, 1]],
     "points": [[0, 0, -1], [0.5, 0.2, 0.8], [0.1, -0.1, -0.05], [2, 0.5, 0.3], [0.3, 0.3, 0.1]]},
    {"id": "hyperboloid1", "f": "x^2+y^2-z^2-1", "box": [[-3, 3], [-3, 3], [-3, 3]],
     "points": [[0.2, 0.1, 0.3], [3, 1, 2], [0, 0, 0.5], [-1.5, 2, -2.5], [1.2, 0.1, 0]]},
    {"id": "hyperboloid2", "f": "z^2-x^2-y^2-1", "box": [[-3, 3], [-3, 3], [-3, 3]],
     "points": [[0.5, 0.2, 0.1], [1, 1, 3], [0.2, -0.3, -1.2], [2.5, 0, 0.4], [0, 0, 1.75]]},
    {"id": "clipped_sphere", "f": "x^2+y^2+z^2-4", "box": [[0, 1.5], [0, 1.5], [0, 1.5]],
     "points": [[3, 0.2, 0.1], [0.2, 0.2, 0.2], [3, -1, -1], [1.4, 1.4, 3], [-1, 0.5, 0.7], [2, 2, 2]]},
    {"id": "clipped_plane", "f": "x+y+z-1", "box": [[0, 1], [0, 1], [0, 1]],
     "points": [[2, -1, -1], [1, 1, -1], [0.5, 0.3, 0.9], [0.2, 0.2, 0.2], [-1, 2, -1]]},
    {"id": "goursat", "f": "x^4+y^4+z^4-5*(x^2+y^2+z^2)+11.8", "box": [[-3, 3], [-3, 3], [-3, 3]],
     "points": [[3, 2.5, 2], [0.1, 0.2, 0.15], [2.5, 0.3, 0.2], [1.1, 0.9, 1.3], [-2, 2.5, -0.5]]},
    {"id": "gyroid", "f": "sin(x)*cos(y)+sin(y)*cos(z)+sin(z)*cos(x)", "box": [[-2, 2], [-2, 2], [-2, 2]],
     "points": [[0.3, 0.2, -0.4], [1.5, -1.0, 0.7], [2.5, 2.4, 2.3], [-1.2, 0.4, 1.9], [0.9, 0.8, 0.1]]},
    {"id": "blend", "f": "(x^2+y^2+z^2-1)*((x-1.8)^2+y^2+z^2-1)-0.2", "box": [[-2, 3.5], [-2, 2], [-2, 2]],
     "points": [[0.9, 0.5, 0.1], [0.9, 0.05, 0.02], [-2, 0.3, 0.2], [3, 1, 1], [0.2, 0.1, 0.3]]},
]


def parse(formula):
    return sympy.sympify(formula.replace("^", "**"), rational=True)


class Surface:
    def __init__(self, case, lines):
        self.f = parse(case["f"])
        self.grad = [sympy.diff(self.f, v) for v in (X, Y, Z)]
        self.hess = [[sympy.diff(g, v) for v in (X, Y, Z)] for g in self.grad]
        self.box = [[sympy.Rational(float(lo)), sympy.Rational(float(hi))] for lo, hi in case["box"]]
        self.boxf = [[float(a), float(b)] for a, b in case["box"]]
        self.fn = sympy.lambdify((X, Y, Z), self.f, "math")
        self.mf = sympy.lambdify((X, Y, Z), self.f, "mpmath")
        self.mg = sympy.lambdify((X, Y, Z), self.grad, "mpmath")
        self.mh = sympy.lambdify((X, Y, Z), self.hess, "mpmath")
        self.lines = lines
        self.samples = self.sample_lines()
        self.tree = cKDTree(np.array([s[0] for s in self.samples]))

    def inside(self, x, axis_fixed=None):
        for k in range(3):
            lo, hi = self.boxf[k]
            if k == axis_fixed:
                continue
            if not (mpmath.mpf(lo) <= x[k] <= mpmath.mpf(hi)):
                return False
        return True

    def roots_on_line(self, a, b, n=400):
        """Sign changes of f along the segment a -> b (doubles), refined by brentq."""
        a = np.array(a, float)
        b = np.array(b, float)
        ts = np.linspace(0.0, 1.0, n + 1)
        vals = [self.fn(*(a + t * (b - a))) for t in ts]
        out = []
        for i in range(n):
            if vals[i] == 0.0:
                out.append(ts[i])
            elif vals[i] * vals[i + 1] < 0.0:
                out.append(brentq(lambda t: self.fn(*(a + t * (b - a))), ts[i], ts[i + 1], xtol=1e-15))
        if vals[-1] == 0.0:
            out.append(1.0)
        return [a + t * (b - a) for t in out]

    def sample_lines(self):
        """Surface points on lines parallel to each axis; face samples carry their face."""
        samples = []  # (point, face) with face = None or (axis, bound index)
        for k in range(3):
            i, j = (k + 1) % 3, (k + 2) % 3
            gi = np.linspace(self.boxf[i][0], self.boxf[i][1], self.lines)
            gj = np.linspace(self.boxf[j][0], self.boxf[j][1], self.lines)
            for u, v in itertools.product(gi, gj):
                a = [0.0] * 3
                a[i], a[j], a[k] = u, v, self.boxf[k][0]
                b = list(a)
                b[k] = self.boxf[k][1]
                for x in self.roots_on_line(a, b):
                    face = None
                    for axis in (i, j):
                        for side in (0, 1):
                            if x[axis] == self.boxf[axis][side]:
                                face = (axis, side)
                    samples.append((x, face))
        return samples

    def newton(self, p, x0, fixed=None):
        """Lagrange system in mpmath; fixed = (axis, value) for a face."""
        p = [mpmath.mpf(c) for c in p]
        g0 = [mpmath.mpf(c) for c in self.mg(*[mpmath.mpf(c) for c in x0])]
        den = sum(g0[k] ** 2 for k in range(3) if fixed is None or k != fixed[0])
        if den == 0:
            return None
        lam0 = sum(g0[k] * (p[k] - x0[k]) for k in range(3) if fixed is None or k != fixed[0]) / den
        free = [k for k in range(3) if fixed is None or k != fixed[0]]

        def point(v):
            x = [None] * 3
            for n, k in enumerate(free):
                x[k] = v[n]
            if fixed is not None:
                x[fixed[0]] = fixed[1]
            return x

        def system(*v):
            x = point(v)
            g = self.mg(*x)
            lam = v[-1]
            eqs = [x[k] - p[k] + lam * g[k] for k in free]
            eqs.append(self.mf(*x))
            return eqs

        def jac(*v):
            x = point(v)
            g = self.mg(*x)
            h = self.mh(*x)
            lam = v[-1]
            rows = []
            for r in free:
                rows.append([(1 if r == c else 0) + lam * h[r][c] for c in free] + [g[r]])
            rows.append([g[c] for c in free] + [0])
            return mpmath.matrix(rows)

        start = [mpmath.mpf(x0[k]) for k in free] + [lam0]
        try:
            v = mpmath.findroot(system, start, J=jac, tol=mpmath.mpf(10) ** -45, maxsteps=60)
        except (ZeroDivisionError, ValueError, TypeError):
            return None
        v = list(v) if hasattr(v, "__iter__") else [v]
        x = point(v)
        if max(abs(e) for e in system(*v)) > mpmath.mpf(10) ** -40:
            return None
        return x

    def edge_points(self):
        out = []
        for k in range(3):
            i, j = (k + 1) % 3, (k + 2) % 3
            for si, sj in itertools.product((0, 1), (0, 1)):
                a = [0.0] * 3
                a[i], a[j], a[k] = self.boxf[i][si], self.boxf[j][sj], self.boxf[k][0]
                b = list(a)
                b[k] = self.boxf[k][1]
                for x in self.roots_on_line(a, b, 4000):
                    xm = [mpmath.mpf(c) for c in x]
                    t0 = xm[k]
                    try:
                        t = mpmath.findroot(lambda t: self.mf(*[t if c == k else xm[c] for c in range(3)]), t0)
                    except (ZeroDivisionError, ValueError):
                        t = t0
                    xm[k] = t
                    if self.inside(xm):
                        out.append(xm)
        # corners where f vanishes exactly
        for c in itertools.product(*self.box):
            if self.f.subs({X: c[0], Y: c[1], Z: c[2]}) == 0:
                out.append([mpmath.mpf(sympy.Rational(v).p) / sympy.Rational(v).q for v in c])
        return out

    def singular_points(self):
        grid = [np.linspace(lo, hi, 21) for lo, hi in self.boxf]
        scored = []
        gradf = sympy.lambdify((X, Y, Z), self.grad, "math")
        for x in itertools.product(*grid):
            scored.append((sum(g * g for g in gradf(*x)), x))
        scored.sort()
        out = []
        for _, x in scored[:8]:
            try:
                s = mpmath.findroot(lambda a, b, c: self.mg(a, b, c), [mpmath.mpf(v) for v in x],
                                    J=lambda a, b, c: mpmath.matrix(self.mh(a, b, c)), maxsteps=60)
            except (ZeroDivisionError, ValueError, TypeError):
                continue
            s = list(s)
            if abs(self.mf(*s)) < mpmath.mpf(10) ** -40 and self.inside(s):
                if all(max(abs(s[k] - t[k]) for k in range(3)) > 1e-20 for t in out):
                    out.append(s)
        return out


def location(surface, x):
    at = sum(1 for k in range(3) for b in surface.boxf[k] if abs(x[k] - mpmath.mpf(b)) < mpmath.mpf(10) ** -40)
    return ["interior", "box-face", "box-edge", "box-corner"][at]


def reference(surface, p, edges, singular):
    pm = [mpmath.mpf(c) for c in p]
    dist = lambda x: mpmath.sqrt(sum((x[k] - pm[k]) ** 2 for k in range(3)))
    cands = []
    for x in edges:
        cands.append((dist(x), x, location(surface, x)))
    for x in singular:
        cands.append((dist(x), x, "singular-point"))
    pts = np.array([s[0] for s in surface.samples])
    d2 = ((pts - np.array(p, float)) ** 2).sum(axis=1)
    h = max(b - a for a, b in surface.boxf) / (surface.lines - 1)
    order = np.argsort(d2)
    seeds = set(order[:12].tolist())
    for n, near in enumerate(surface.tree.query_ball_point(pts, 3 * h)):
        if d2[n] <= d2[near].min():
            seeds.add(n)
    for n in seeds:
        x0, face = surface.samples[n]
        x = surface.newton(p, [mpmath.mpf(c) for c in x0])
        if x is not None and surface.inside(x):
            cands.append((dist(x), x, location(surface, x)))
        faces = [face] if face else []
        for k in range(3):
            for side in (0, 1):
                if abs(x0[k] - surface.boxf[k][side]) <= 2 * h:
                    faces.append((k, side))
        for k, side in faces:
            xf = surface.newton(p, [mpmath.mpf(c) for c in x0], (k, mpmath.mpf(surface.boxf[k][side])))
            if xf is not None and surface.inside(xf):
                cands.append((dist(xf), xf, location(surface, xf)))
    cands.sort(key=lambda c: c[0])
    best = cands[0]
    nearest_sample = mpmath.sqrt(mpmath.mpf(float(d2.min())))
    if nearest_sample < best[0] - mpmath.mpf(10) ** -9 * (1 + best[0]):
        raise RuntimeError("a sample is nearer than every candidate at p = %s" % (p,))
    minima = []
    for d, x, t in cands:
        if all(max(abs(x[k] - m[1][k]) for k in range(3)) > 1e-12 for m in minima):
            minima.append((d, x, t))
    return best, minima[:12]


def compute(case, lines):
    surface = Surface(case, lines)
    edges = surface.edge_points()
    singular = surface.singular_points()
    out = {"id": case["id"], "kind": "implicit_surface", "equation": case["f"],
           "domain": {"x": surface.boxf[0], "y": surface.boxf[1], "z": surface.boxf[2]},
           "generated_by": "tests/tools/gen_surface_implicit_reference.py --lines %d" % lines, "points": []}
    for p in case["points"]:
        (d, x, t), minima = reference(surface, [float(c) for c in p], edges, singular)
        out["points"].append({
            "p": [float(c) for c in p], "distance": float(d), "distance_str": mpmath.nstr(d, 30),
            "foot": [float(c) for c in x], "type": t,
            "ambiguous": len(minima) > 1 and abs(minima[1][0] - d) <= mpmath.mpf(10) ** -9 * (1 + d)
            and max(abs(minima[1][1][k] - x[k]) for k in range(3)) > 1e-8,
            "local_minima": [{"distance": float(m[0]), "foot": [float(c) for c in m[1]], "type": m[2]}
                             for m in minima]})
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("command", nargs="?", default="make")
    ap.add_argument("file", nargs="?")
    ap.add_argument("--lines", type=int, default=41)
    ap.add_argument("--out")
    ap.add_argument("--case")
    a = ap.parse_args()
    if a.command == "check":
        data = json.load(open(a.file))
        passed = failed = 0
        for stored in data["cases"]:
            if a.case and stored["id"] != a.case:
                continue
            case = next(c for c in CASES if c["id"] == stored["id"])
            fresh = compute(case, a.lines)
            for s, f in zip(stored["points"], fresh["points"]):
                if mpmath.mpf(s["distance_str"]) - mpmath.mpf(f["distance_str"]) == 0 or \
                        abs(mpmath.mpf(s["distance_str"]) - mpmath.mpf(f["distance_str"])) <= mpmath.mpf(10) ** -28:
                    passed += 1
                else:
                    failed += 1
                    print("%s p=%s: stored %s, now %s" % (stored["id"], s["p"], s["distance_str"], f["distance_str"]))
        print("%d passed, %d failed" % (passed, failed))
        return 1 if failed else 0
    cases = [compute(c, a.lines) for c in CASES if not a.case or c["id"] == a.case]
    text = json.dumps({"format": "footpoint implicit surface references",
                       "generated_by": "tests/tools/gen_surface_implicit_reference.py --lines %d" % a.lines,
                       "cases": cases}, indent=1)
    if a.out:
        open(a.out, "w").write(text + "\n")
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
