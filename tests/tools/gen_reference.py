#!/usr/bin/python3
"""Reference nearest points for footpoint's tests and benchmarks, to 50 digits.

For a geometry and a set of points it computes the global nearest point over the closed domain
(surfaces: edges and corners included; parametric curves: endpoints included; implicit curves:
the part of the curve inside the box, with its box-face crossings and singular points), every
local minimum of the distance it finds, and writes them in the JSON shape of tests/data/*.json.
It can also recompute an existing data file and report where it disagrees (`check`).

Method (independent of footpoint's C++ code: sympy for the formulas and their exact derivatives,
numpy for dense sampling, mpmath at 60 digits for the polishing):
  parametric surface  a grid over the domain; every discrete local minimum of |p - s|^2 among the
                      interior nodes is descended with bounded L-BFGS-B (doubles) and, when it
                      ends inside the domain, polished by Newton on grad |p - s|^2 / 2 = 0 in
                      mpmath (a local minimum needs a positive semidefinite Hessian). Each edge is
                      a curve of its own (the 1-D search below), kept when the derivative across
                      it points outwards (the Karush-Kuhn-Tucker sign condition); each corner is
                      kept when both derivatives do. A second grid, through the cell centres,
                      must not find a point nearer than the answer (else it seeds another search).
  parametric curve    dense samples of t; every discrete local minimum is polished by a
                      safeguarded Newton iteration on (c(t) - p) . c'(t) = 0 inside the bracket of
                      its neighbouring samples; an endpoint is kept when the distance grows inwards.
  implicit curve      the box is subdivided with interval arithmetic on f (2-D) or f1, f2 (3-D):
                      a cell whose enclosure excludes zero holds no point of the curve; the
                      surviving cells of size h = (bounding box diagonal) / resolution are projected
                      onto the curve by Gauss-Newton (minimum-norm steps) to dense samples. A
                      sample nearer to p than its neighbours within a few h seeds Newton on the
                      Lagrange conditions {f_i = 0, (p - x) parallel to the normal space} in mpmath.
                      Box-face crossings (f_i = 0 on the face) and singular points (f_i = 0 and
                      grad f1 x grad f2 = 0, resp. grad f = 0, by Gauss-Newton) are candidates too.
Formulas are muparser syntax (^ for power, _pi, _e, ln = log natural, log10, log2); decimal
literals are read as the exact decimals they spell, points and domain bounds as the exact binary
doubles the service receives. Results are printed with 50 significant digits (the *_str fields).

Usage (points as -p=X,Y[,Z], repeatable; the = keeps a leading minus from reading as an option):
  gen_reference.py surface --x "u+v" --y "sin(u)+2*cos(v)" --z "sin(u+v)" --u=-3,3 --v=-3,3 -p=1,2,2
  gen_reference.py paramcurve --x "cos(t)" --y "sin(t)" --z "0.2*t" --t=0,12.566370614359172 -p=1.5,0.3,0.7
  gen_reference.py implicit2d --f "y^2-x^3" --box=-1,2,-2,2 -p=-1,0.1
  gen_reference.py curve3d --f1 "x^2+y^2+z^2-4" --f2 "(x-1)^2+y^2-1" --box=-3,3,-3,3,-3,3 -p=2.5,0.1,0.05
  gen_reference.py geometry GEOMETRY.json -p=...   (a geometry as POST /v1/geometries takes it)
  gen_reference.py check tests/data/surface_torus.json [--case ID] [--max-points N] [--quick] [-v]
                   [--grid N | --samples N | --resolution R: denser than the file was made with]
Options of the generating commands: --id, --title, --out FILE (default stdout); --grid N
(surfaces, nodes per side, default 201), --samples N (parametric curves, default 20001),
--resolution R (implicit curves, default 1000). The output records its own command line in
"generated_by". `check` recomputes every point of a file in any of the shapes of tests/data/ and
prints one line per disagreement and a closing "N passed, M failed" (exit code 1 on a failure);
--quick samples 4x coarser (for the test suite: it keeps the tool working, it is not a check of
the data). Run with Debian's python3-numpy, python3-scipy, python3-sympy, python3-mpmath.
"""
import argparse
import contextlib
import json
import math
import os
import re
import shlex
import sys

import mpmath
import numpy as np
import sympy as sp
from mpmath import mp, mpf
from scipy import optimize
from scipy.spatial import cKDTree

WORK_DIGITS = 60      # mpmath precision of every polishing step
OUT_DIGITS = 50       # significant digits of the *_str fields
TIE_RTOL = 1e-9       # two distinct minima this close in distance make the answer ambiguous
MAX_LISTED = 12       # local minima (and parameter pairs of one foot) stored per point
mp.dps = WORK_DIGITS

# ---------------------------------------------------------------------------------------------
# muparser formulas -> sympy
# ---------------------------------------------------------------------------------------------
FUNCTIONS = {
    'sin': sp.sin, 'cos': sp.cos, 'tan': sp.tan, 'asin': sp.asin, 'acos': sp.acos, 'atan': sp.atan,
    'sinh': sp.sinh, 'cosh': sp.cosh, 'tanh': sp.tanh, 'asinh': sp.asinh, 'acosh': sp.acosh,
    'atanh': sp.atanh, 'exp': sp.exp, 'ln': sp.log, 'log': sp.log,
    'log10': lambda a: sp.log(a, 10), 'log2': lambda a: sp.log(a, 2), 'sqrt': sp.sqrt,
    'abs': sp.Abs, 'sign': sp.sign, 'min': sp.Min, 'max': sp.Max,
}
CONSTANTS = {'_pi': sp.pi, '_e': sp.E}
TOKEN = re.compile(r'\s*(?:(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)'
                   r'|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<op>[-+*/^(),]))')
SYMBOLS = {name: sp.Symbol(name, real=True) for name in ('u', 'v', 't', 'x', 'y', 'z')}


def exact_double(value):
    """The binary double `value` as an exact rational."""
    return sp.Rational(*float(value).as_integer_ratio())


def parse_formula(text, variables, constants=None):
    """A muparser formula as a sympy expression in the real symbols `variables`."""
    constants = constants or {}
    pieces, names, pos = [], {}, 0
    while pos < len(text):
        m = TOKEN.match(text, pos)
        if not m or m.end() == pos:
            if not text[pos:].strip():
                break
            raise ValueError('cannot read %r at %r' % (text, text[pos:]))
        pos = m.end()
        if m.group('number') is not None:
            key = '_n%d' % len(names)
            names[key] = sp.Rational(m.group('number'))
            pieces.append(key)
        elif m.group('name') is not None:
            word = m.group('name')
            key = '_w_' + word
            if word in variables:
                names[key] = SYMBOLS[word]
            elif word in constants:
                names[key] = sp.Rational(repr(float(constants[word])))
            elif word in FUNCTIONS:
                names[key] = FUNCTIONS[word]
            elif word in CONSTANTS:
                names[key] = CONSTANTS[word]
            else:
                raise ValueError('unknown name %r in %r' % (word, text))
            pieces.append(key)
        else:
            pieces.append('**' if m.group('op') == '^' else m.group('op'))
    return sp.sympify(sp.parse_expr(' '.join(pieces), local_dict=names, evaluate=True))


def numpy_function(args, exprs):
    """exprs (a list) evaluated on numpy arrays, every output broadcast to the arguments' shape."""
    f = sp.lambdify(args, exprs, 'numpy')

    def call(*xs):
        shape = np.broadcast(*[np.asarray(x) for x in xs]).shape
        with np.errstate(all='ignore'):
            return np.array([np.broadcast_to(np.asarray(r, dtype=float), shape) for r in f(*xs)])
    return call


def mp_function(args, exprs):
    f = sp.lambdify(args, exprs, 'mpmath')
    return lambda *xs: [mpf(r) for r in f(*xs)]


@contextlib.contextmanager
def quiet_stdout():
    sys.stdout.flush()
    saved = os.dup(1)
    with open(os.devnull, 'w') as null:
        os.dup2(null.fileno(), 1)
    try:
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def text(x):
    return mpmath.nstr(x, OUT_DIGITS, strip_zeros=False) if x != 0 else '0.0'


def norm(v):
    return mp.sqrt(sum(c * c for c in v))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


# ---------------------------------------------------------------------------------------------
# local minima -> the JSON record
# ---------------------------------------------------------------------------------------------
class Minimum:
    def __init__(self, kind, foot, p, params=None):
        self.kind, self.foot, self.params = kind, foot, params
        self.distance = norm([a - b for a, b in zip(foot, p)])
        self.all_params = [params] if params is not None else []


def record(minima, p, scale, extra=None):
    """The nearest of `minima` and the distinct local minima, best first, merged by foot point
    (a foot reached from several parameters keeps them all: seams, poles, coverings)."""
    if not minima:
        raise RuntimeError('no local minimum found for p = %s' % (p,))
    minima = sorted(minima, key=lambda m: m.distance)
    distinct = []
    same_foot = mpf(10) ** -12 * max(1, scale)
    for m in minima:
        for d in distinct:
            if norm([a - b for a, b in zip(m.foot, d.foot)]) <= same_foot:
                for q in m.all_params:
                    if all(max(abs(a - b) for a, b in zip(q, o)) > same_foot for o in d.all_params):
                        d.all_params.append(q)
                break
        else:
            distinct.append(m)
    best = distinct[0]
    ambiguous = len(distinct) > 1 and distinct[1].distance - best.distance <= \
        TIE_RTOL * best.distance + mpf(10) ** -30 * max(1, scale)
    out = {
        'distance': float(best.distance), 'distance_str': text(best.distance),
        'foot': [float(c) for c in best.foot], 'foot_str': [text(c) for c in best.foot],
        'params': None if best.params is None else [float(c) for c in best.params],
        'params_str': None if best.params is None else [text(c) for c in best.params],
        'type': best.kind, 'ambiguous': bool(ambiguous), 'n_local_minima': len(distinct),
    }
    if len(best.all_params) > 1:
        out['params_all'] = [[float(c) for c in q] for q in best.all_params[:MAX_LISTED]]
        out['params_nonunique'] = True
    out['local_minima'] = []
    for m in distinct[:MAX_LISTED]:
        e = {'type': m.kind, 'distance': float(m.distance), 'distance_str': text(m.distance),
             'foot': [float(c) for c in m.foot]}
        if m.params is not None:
            e['params'] = [float(c) for c in m.params]
        out['local_minima'].append(e)
    out.update(extra or {})
    return out


# ---------------------------------------------------------------------------------------------
# a curve c(t), t in [t0, t1]: parametric curves and the edges of a surface
# ---------------------------------------------------------------------------------------------
class Curve1D:
    """points(t) -> (dim, n) doubles; jet(t) -> (c, c', c'') in mpmath."""

    def __init__(self, points, jet, t0, t1, samples):
        self.jet, self.t0, self.t1 = jet, float(t0), float(t1)
        self.ts = np.linspace(self.t0, self.t1, samples)
        self.ts[-1] = self.t1
        self.cs = points(self.ts)

    def slope(self, t, p):
        """(c(t) - p) . c'(t) and its derivative |c'|^2 + (c - p) . c''."""
        c, c1, c2 = self.jet(t)
        r = [a - b for a, b in zip(c, p)]
        return dot(r, c1), dot(c1, c1) + dot(r, c2), c

    def polish(self, a, b, t, p):
        """Newton on the slope from t, kept inside the bracket [a, b] (bisection when a step
        leaves it or the curvature term is not positive)."""
        a, b, t = mpf(a), mpf(b), mpf(t)
        tol = mpf(10) ** (8 - WORK_DIGITS) * (self.t1 - self.t0)
        for _ in range(300):
            g, h, _c = self.slope(t, p)
            if g == 0:
                break
            if g > 0:
                b = min(b, t)
            else:
                a = max(a, t)
            step = -g / h if h > 0 else None
            if step is None or not (a <= t + step <= b):
                step = (a + b) / 2 - t
            t += step
            if abs(step) <= tol or b - a <= tol:
                break
        g, h, c = self.slope(t, p)
        return t, g, h, c

    def local_minima(self, p, candidates=40):
        """[(t, c, kind)] with kind 'interior', 'start' or 'end', every local minimum of |c - p|."""
        pm = [mpf(x) for x in p]
        d = ((self.cs - np.asarray(p, dtype=float)[:, None]) ** 2).sum(0)
        n = len(self.ts)
        # every discrete local minimum, the end samples included: a minimum between an end
        # sample and its neighbour has no interior sample below its neighbours
        padded = np.concatenate(([np.inf], d, [np.inf]))
        inner = np.nonzero((d <= padded[:-2]) & (d <= padded[2:]))[0]
        inner = inner[np.argsort(d[inner], kind='stable')][:candidates]
        out = []
        for i in inner:
            t, g, h, c = self.polish(self.ts[max(i - 1, 0)], self.ts[min(i + 1, n - 1)], self.ts[i], pm)
            if self.t0 < t < self.t1 and h >= 0 and abs(g) <= mpf(10) ** (20 - WORK_DIGITS) * (1 + norm(c) + norm(pm)) ** 2:
                if not any(abs(t - o[0]) <= mpf(10) ** -20 * (self.t1 - self.t0) for o in out):
                    out.append((t, c, 'interior'))
        for t, inward in ((mpf(self.t0), 1), (mpf(self.t1), -1)):
            g, _h, c = self.slope(t, pm)
            if inward * g >= -mpf(10) ** (20 - WORK_DIGITS) * (1 + norm(c) + norm(pm)) ** 2:
                out.append((t, c, 'start' if inward > 0 else 'end'))
        return out


# ---------------------------------------------------------------------------------------------
# parametric surfaces
# ---------------------------------------------------------------------------------------------
class ParametricSurface:
    kind = 'surface'

    def __init__(self, formulas, domain, grid=201, constants=None):
        u, v = SYMBOLS['u'], SYMBOLS['v']
        s = [parse_formula(f, ('u', 'v'), constants) for f in formulas]
        su, sv = [sp.diff(e, u) for e in s], [sp.diff(e, v) for e in s]
        second = [sp.diff(e, u) for e in su] + [sp.diff(e, v) for e in su] + [sp.diff(e, v) for e in sv]
        self.points = numpy_function((u, v), s)
        self.tangents = numpy_function((u, v), su + sv)
        self.jet = mp_function((u, v), s + su + sv + second)
        (self.u0, self.u1), (self.v0, self.v1) = [(float(a), float(b)) for a, b in domain]
        self.grid = int(grid)
        us = np.linspace(self.u0, self.u1, self.grid)
        vs = np.linspace(self.v0, self.v1, self.grid)
        us[-1], vs[-1] = self.u1, self.v1
        self.us, self.vs = us, vs
        self.nodes = self.points(*np.meshgrid(us, vs, indexing='ij'))
        cu, cv = (us[1:] + us[:-1]) / 2, (vs[1:] + vs[:-1]) / 2
        self.centre_params = np.meshgrid(cu, cv, indexing='ij')
        self.centres = self.points(*self.centre_params)
        if not (np.all(np.isfinite(self.nodes)) and np.all(np.isfinite(self.centres))):
            raise ValueError('the surface is not finite on its domain')
        flat = self.nodes.reshape(3, -1)
        self.scale = float(np.linalg.norm(flat.max(1) - flat.min(1)))
        edge_samples = max(4001, 8 * self.grid)
        self.edges = []
        for name, fixed, along in (('u=umin', ('u', self.u0), (self.v0, self.v1)),
                                   ('u=umax', ('u', self.u1), (self.v0, self.v1)),
                                   ('v=vmin', ('v', self.v0), (self.u0, self.u1)),
                                   ('v=vmax', ('v', self.v1), (self.u0, self.u1))):
            self.edges.append((name, fixed, self.edge_curve(fixed, along, edge_samples)))

    def edge_curve(self, fixed, along, samples):
        which, value = fixed
        mv = mpf(value)
        if which == 'u':
            def points(t):
                return self.points(np.full_like(t, value), t)

            def jet(t):
                j = self.jet(mv, t)
                return j[0:3], j[6:9], j[15:18]
        else:
            def points(t):
                return self.points(t, np.full_like(t, value))

            def jet(t):
                j = self.jet(t, mv)
                return j[0:3], j[3:6], j[9:12]
        return Curve1D(points, jet, along[0], along[1], samples)

    def half_gradient(self, u, v, p):
        """s, s_u, s_v, and the gradient and Hessian of |s - p|^2 / 2, in mpmath."""
        j = self.jet(u, v)
        s, su, sv, suu, suv, svv = j[0:3], j[3:6], j[6:9], j[9:12], j[12:15], j[15:18]
        r = [a - b for a, b in zip(s, p)]
        g = (dot(r, su), dot(r, sv))
        h = (dot(su, su) + dot(r, suu), dot(su, sv) + dot(r, suv), dot(sv, sv) + dot(r, svv))
        return s, su, sv, g, h

    def newton(self, u, v, p):
        """Newton on grad |s - p|^2 / 2 from (u, v), damped to a descent of the distance: the
        interior local minimum it reaches (u, v, s) or None (it leaves the domain, or ends at a
        saddle or a maximum)."""
        u, v = mpf(u), mpf(v)
        ru, rv = self.u1 - self.u0, self.v1 - self.v0
        tol = mpf(10) ** (8 - WORK_DIGITS)
        for _ in range(100):
            s, su, sv, g, (a, b, c) = self.half_gradient(u, v, p)
            det = a * c - b * b
            if det > 0 and a > 0:
                du, dv = (-c * g[0] + b * g[1]) / det, (b * g[0] - a * g[1]) / det
            else:  # not convex here: a gradient step scaled by the Hessian's size
                scale = abs(a) + abs(c) + mpf(10) ** -30
                du, dv = -g[0] / scale, -g[1] / scale
            shrink = max(abs(du) / (0.05 * ru), abs(dv) / (0.05 * rv), 1)
            du, dv = du / shrink, dv / shrink
            u, v = u + du, v + dv
            if abs(du) <= tol * ru and abs(dv) <= tol * rv:
                break
            if not (self.u0 - 0.1 * ru <= u <= self.u1 + 0.1 * ru and self.v0 - 0.1 * rv <= v <= self.v1 + 0.1 * rv):
                return None
        s, su, sv, g, (a, b, c) = self.half_gradient(u, v, p)
        size = norm([x - y for x, y in zip(s, p)]) * (norm(su) + norm(sv)) + mpf(10) ** -40
        if abs(g[0]) + abs(g[1]) > mpf(10) ** (25 - WORK_DIGITS) * size:
            return None
        if not (self.u0 <= u <= self.u1 and self.v0 <= v <= self.v1):
            return None
        smallest = (a + c) / 2 - mp.sqrt(((a - c) / 2) ** 2 + b * b)
        if smallest < -mpf(10) ** -10 * (dot(su, su) + dot(sv, sv) + mpf(10) ** -60):
            return None
        return u, v, s

    def descend(self, start, p):
        """Bounded L-BFGS-B in doubles from a grid node: where the basin of the node ends."""
        pa = np.asarray(p, dtype=float)

        def f(x):
            s = self.points(x[0], x[1])
            t = self.tangents(x[0], x[1])
            r = s - pa
            return float((r * r).sum()), np.array([2 * float((r * t[0:3]).sum()), 2 * float((r * t[3:6]).sum())])
        with quiet_stdout():  # the Fortran code of L-BFGS-B prints its line search's troubles
            res = optimize.minimize(f, start, jac=True, method='L-BFGS-B',
                                    bounds=[(self.u0, self.u1), (self.v0, self.v1)],
                                    options={'ftol': 1e-15, 'gtol': 1e-12, 'maxiter': 500})
        return res.x

    def interior_minima(self, starts, p, pm, found):
        """Newton from each start and from where L-BFGS-B descends from it (a first step of
        L-BFGS-B may jump to another basin; Newton's steps are held to 5% of the domain)."""
        ru, rv = self.u1 - self.u0, self.v1 - self.v0
        seen = []
        for start in starts:
            for x in (start, self.descend(start, p)):
                if any(abs(x[0] - a) <= 1e-10 * ru and abs(x[1] - b) <= 1e-10 * rv for a, b in seen):
                    continue
                seen.append((x[0], x[1]))
                out = self.newton(x[0], x[1], pm)
                if out is not None:
                    found.append(Minimum('interior', out[2], pm, [out[0], out[1]]))

    def project(self, p, candidates=40):
        pm = [mpf(x) for x in p]
        pa = np.asarray(p, dtype=float)[:, None, None]
        d = ((self.nodes - pa) ** 2).sum(0)
        padded = np.pad(d, 1, constant_values=np.inf)
        n = self.grid
        is_min = np.ones_like(d, dtype=bool)
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                if di or dj:
                    is_min &= d <= padded[1 + di:1 + di + n, 1 + dj:1 + dj + n]
        ii, jj = np.nonzero(is_min)
        order = np.argsort(d[ii, jj], kind='stable')[:candidates]
        found = []
        self.interior_minima([(self.us[ii[k]], self.vs[jj[k]]) for k in order], p, pm, found)
        tol = mpf(10) ** (20 - WORK_DIGITS)
        for name, (which, value), curve in self.edges:
            outward = 1 if name.endswith('min') else -1
            if np.ptp(curve.cs, axis=1).max() <= 1e-14 * max(1.0, self.scale):
                # the edge is one point (a cone's apex, a sphere's pole): a minimum wherever the
                # derivative across the edge points outwards; the best such parameter
                t = curve.ts
                u, v = (np.full_like(t, value), t) if which == 'u' else (t, np.full_like(t, value))
                tangents = self.tangents(u, v)
                r = curve.cs - np.asarray(p, dtype=float)[:, None]
                across = (r * (tangents[0:3] if which == 'u' else tangents[3:6])).sum(0)
                k = int(np.argmax(outward * across))
                if outward * across[k] >= 0:
                    uk, vk = (mpf(value), mpf(t[k])) if which == 'u' else (mpf(t[k]), mpf(value))
                    s = self.half_gradient(uk, vk, pm)[0]
                    found.append(Minimum('edge(%s)' % name, s, pm, [uk, vk]))
                continue
            for t, c, kind in curve.local_minima(p, candidates):
                if kind != 'interior':
                    continue  # corners below
                u, v = (mpf(value), t) if which == 'u' else (t, mpf(value))
                s, su, sv, g, _h = self.half_gradient(u, v, pm)
                across = g[0] if which == 'u' else g[1]
                size = norm([a - b for a, b in zip(s, pm)]) * (norm(su) + norm(sv)) + mpf(10) ** -40
                if outward * across >= -tol * size:
                    found.append(Minimum('edge(%s)' % name, s, pm, [u, v]))
        for u, ue in ((self.u0, 'umin'), (self.u1, 'umax')):
            for v, ve in ((self.v0, 'vmin'), (self.v1, 'vmax')):
                s, su, sv, g, _h = self.half_gradient(mpf(u), mpf(v), pm)
                size = norm([a - b for a, b in zip(s, pm)]) * (norm(su) + norm(sv)) + mpf(10) ** -40
                su_ok = (1 if ue == 'umin' else -1) * g[0] >= -tol * size
                sv_ok = (1 if ve == 'vmin' else -1) * g[1] >= -tol * size
                if su_ok and sv_ok:
                    found.append(Minimum('corner(u=%s,v=%s)' % (ue, ve), s, pm, [mpf(u), mpf(v)]))
        # the answer must not be farther than any node or cell centre of the grids
        verified = False
        for _ in range(6):
            best = min(m.distance for m in found) if found else mpf('inf')
            dc = ((self.centres - pa) ** 2).sum(0)
            k = np.unravel_index(np.argmin(dc), dc.shape)
            kn = np.unravel_index(np.argmin(d), d.shape)
            nearer = [(float(dc[k]), (self.centre_params[0][k], self.centre_params[1][k])),
                      (float(d[kn]), (self.us[kn[0]], self.vs[kn[1]]))]
            nearer = [q for dq, q in nearer if dq < float(best) ** 2 * (1 - 1e-12) - 1e-300]
            if not nearer:
                verified = True
                break
            before = len(found)
            self.interior_minima(nearer, p, pm, found)
            if len(found) == before:
                break
        return record(found, pm, self.scale, {'verified': verified})


# ---------------------------------------------------------------------------------------------
# parametric curves (2-D or 3-D)
# ---------------------------------------------------------------------------------------------
class ParametricCurve:
    kind = 'paramcurve'

    def __init__(self, formulas, domain, samples=20001, constants=None):
        t = SYMBOLS['t']
        c = [parse_formula(f, ('t',), constants) for f in formulas]
        c1 = [sp.diff(e, t) for e in c]
        c2 = [sp.diff(e, t) for e in c1]
        self.dim = len(c)
        jet = mp_function((t,), c + c1 + c2)
        k = self.dim

        def mp_jet(tt):
            j = jet(tt)
            return j[0:k], j[k:2 * k], j[2 * k:3 * k]
        self.curve = Curve1D(numpy_function((t,), c), mp_jet, domain[0], domain[1], samples)
        if not np.all(np.isfinite(self.curve.cs)):
            raise ValueError('the curve is not finite on its domain')
        self.scale = float(np.linalg.norm(self.curve.cs.max(1) - self.curve.cs.min(1)))

    def project(self, p, candidates=40):
        pm = [mpf(x) for x in p]
        kinds = {'interior': 'interior', 'start': 'endpoint(tmin)', 'end': 'endpoint(tmax)'}
        found = [Minimum(kinds[kind], c, pm, [t]) for t, c, kind in self.curve.local_minima(p, candidates)]
        d = np.sqrt(((self.curve.cs - np.asarray(p, dtype=float)[:, None]) ** 2).sum(0)).min()
        best = min(m.distance for m in found)
        return record(found, pm, self.scale, {'verified': bool(float(best) <= d * (1 + 1e-12))})


# ---------------------------------------------------------------------------------------------
# interval enclosures of sympy expressions (vectorised over cells)
# ---------------------------------------------------------------------------------------------
WIDEN = 1e-13   # relative widening of every result for the rounding of double arithmetic


def _widen(lo, hi):
    pad = WIDEN * np.maximum(np.abs(lo), np.abs(hi)) + 1e-300
    return lo - pad, hi + pad


def _mul(a, b):
    with np.errstate(invalid='ignore'):
        c = np.array([a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1]])
        c = np.where(np.isnan(c), 0.0, c)   # 0 * inf
    return _widen(c.min(0), c.max(0))


def _power(a, n):
    lo, hi = a
    if n == 0:
        return np.ones_like(lo), np.ones_like(hi)
    if n < 0:
        plo, phi = _power(a, -n)
        zero = (plo <= 0) & (phi >= 0)
        with np.errstate(divide='ignore'):
            rlo, rhi = 1 / phi, 1 / plo
        return _widen(np.where(zero, -np.inf, rlo), np.where(zero, np.inf, rhi))
    plo, phi = lo ** n, hi ** n
    if n % 2:
        return _widen(plo, phi)
    low = np.where((lo <= 0) & (hi >= 0), 0.0, np.minimum(plo, phi))
    return _widen(low, np.maximum(plo, phi))


def _periodic(fn, shift, lo, hi):
    """sin (shift 0) or cos (shift pi/2): the endpoints' values, and +-1 where a crest is inside."""
    a, b = fn(lo), fn(hi)
    out_lo, out_hi = np.minimum(a, b), np.maximum(a, b)
    # crests of sin(x + shift) at x = pi/2 - shift + 2 k pi, troughs at -pi/2 - shift + 2 k pi
    top = np.ceil((lo - (np.pi / 2 - shift)) / (2 * np.pi)) * 2 * np.pi + np.pi / 2 - shift <= hi
    bottom = np.ceil((lo + np.pi / 2 + shift) / (2 * np.pi)) * 2 * np.pi - np.pi / 2 - shift <= hi
    out_hi = np.where(top | (hi - lo >= 2 * np.pi), 1.0, out_hi)
    out_lo = np.where(bottom | (hi - lo >= 2 * np.pi), -1.0, out_lo)
    return _widen(out_lo, out_hi)


MONOTONE = {sp.exp: np.exp, sp.atan: np.arctan, sp.sinh: np.sinh, sp.tanh: np.tanh, sp.asinh: np.arcsinh}


def enclose(expr, env):
    """Interval enclosure (lo, hi) of expr over the cells env[symbol] = (lo, hi)."""
    shape = next(iter(env.values()))[0].shape
    if expr.is_Symbol:
        return env[expr]
    if expr.is_Number:
        c = float(expr)
        return _widen(np.full(shape, c), np.full(shape, c))
    if expr.is_Add:
        lo, hi = np.zeros(shape), np.zeros(shape)
        for term in expr.args:
            a = enclose(term, env)
            lo, hi = lo + a[0], hi + a[1]
        return _widen(lo, hi)
    if expr.is_Mul:
        out = (np.ones(shape), np.ones(shape))
        for factor in expr.args:
            out = _mul(out, enclose(factor, env))
        return out
    if expr.is_Pow:
        base, e = expr.args
        if e.is_Integer:
            return _power(enclose(base, env), int(e))
        lo, hi = enclose(base, env)
        if e == sp.Rational(1, 2):
            return _widen(np.sqrt(np.maximum(lo, 0)), np.sqrt(np.maximum(hi, 0)))
        ok = lo > 0
        with np.errstate(all='ignore'):
            c = np.array([lo ** float(e), hi ** float(e)])
        return _widen(np.where(ok, c.min(0), -np.inf), np.where(ok, c.max(0), np.inf))
    if expr.func in (sp.sin, sp.cos):
        lo, hi = enclose(expr.args[0], env)
        return _periodic(np.sin, 0.0, lo, hi) if expr.func == sp.sin else _periodic(np.cos, np.pi / 2, lo, hi)
    if expr.func in MONOTONE:
        lo, hi = enclose(expr.args[0], env)
        return _widen(MONOTONE[expr.func](lo), MONOTONE[expr.func](hi))
    if expr.func == sp.cosh:
        lo, hi = enclose(expr.args[0], env)
        top = np.maximum(np.cosh(lo), np.cosh(hi))
        return _widen(np.where((lo <= 0) & (hi >= 0), 1.0, np.minimum(np.cosh(lo), np.cosh(hi))), top)
    if expr.func == sp.log:
        lo, hi = enclose(expr.args[0], env)
        with np.errstate(all='ignore'):
            return _widen(np.where(lo > 0, np.log(lo), -np.inf), np.where(hi > 0, np.log(hi), -np.inf))
    if expr.func == sp.Abs:
        lo, hi = enclose(expr.args[0], env)
        low = np.where((lo <= 0) & (hi >= 0), 0.0, np.minimum(np.abs(lo), np.abs(hi)))
        return low, np.maximum(np.abs(lo), np.abs(hi))
    return np.full(shape, -np.inf), np.full(shape, np.inf)   # no enclosure known: the whole line


# ---------------------------------------------------------------------------------------------
# implicit curves: f(x, y) = 0 in a rectangle, f1 = f2 = 0 in a box
# ---------------------------------------------------------------------------------------------
class ImplicitCurve:
    def __init__(self, equations, box, resolution=1000, constants=None, max_cells=4_000_000):
        self.dim = len(box)
        if len(equations) != self.dim - 1:
            raise ValueError('an implicit curve needs 1 equation in 2-D, 2 in 3-D')
        self.kind = 'implicit2d' if self.dim == 2 else 'curve3d'
        names = ('x', 'y', 'z')[:self.dim]
        self.vars = [SYMBOLS[n] for n in names]
        self.f = [parse_formula(e, names, constants) for e in equations]
        self.box = np.array([[float(a), float(b)] for a, b in box])
        grad = [[sp.diff(f, x) for x in self.vars] for f in self.f]
        self.np_f = numpy_function(self.vars, self.f)
        self.np_grad = numpy_function(self.vars, [g for row in grad for g in row])
        # the tangent: perp(grad f) in 2-D, grad f1 x grad f2 in 3-D
        if self.dim == 2:
            tangent = [-grad[0][1], grad[0][0]]
        else:
            a, b = grad
            tangent = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        self.tangent_exprs = tangent
        self.np_tangent = numpy_function(self.vars, tangent)
        self.mp_f = mp_function(self.vars, self.f)
        self.mp_grad = mp_function(self.vars, [g for row in grad for g in row])
        self.mp_hess = mp_function(self.vars, [sp.diff(g, x) for row in grad for g in row for x in self.vars])
        ps = [sp.Symbol('p%d' % i, real=True) for i in range(self.dim)]
        lagrange = list(self.f) + [sum((x - q) * t for x, q, t in zip(self.vars, ps, tangent))]
        self.mp_lagrange = mp_function(self.vars + ps, lagrange)
        self.mp_lagrange_jac = mp_function(self.vars + ps, [sp.diff(e, x) for e in lagrange for x in self.vars])
        singular = list(self.f) + tangent
        self.mp_singular = mp_function(self.vars, singular)
        self.mp_singular_jac = mp_function(self.vars, [sp.diff(e, x) for e in singular for x in self.vars])
        self.singular_exprs = singular
        self.resolution, self.max_cells = resolution, max_cells
        self.discover()

    # --- the curve's samples
    def subdivide(self):
        lo, hi = self.box[:, 0][None, :].copy(), self.box[:, 1][None, :].copy()
        corners = np.array(np.meshgrid(*[[0, 1]] * self.dim, indexing='ij')).reshape(self.dim, -1).T
        while True:
            env = {x: (lo[:, k], hi[:, k]) for k, x in enumerate(self.vars)}
            keep = np.ones(len(lo), dtype=bool)
            for f in self.f:
                flo, fhi = enclose(f, env)
                keep &= (flo <= 0) & (fhi >= 0)
            lo, hi = lo[keep], hi[keep]
            if len(lo) == 0:
                return lo, hi
            extent = hi.max(0) - lo.min(0)
            h = max(float(np.linalg.norm(extent)) / self.resolution, 1e-12 * float(np.linalg.norm(self.box[:, 1] - self.box[:, 0])))
            if (hi - lo).max() <= h:
                return lo, hi
            if len(lo) * len(corners) > self.max_cells:
                raise RuntimeError('more than %d cells: lower --resolution' % self.max_cells)
            mid = (lo + hi) / 2
            new_lo, new_hi = [], []
            for c in corners:
                new_lo.append(np.where(c, mid, lo))
                new_hi.append(np.where(c, hi, mid))
            lo, hi = np.concatenate(new_lo), np.concatenate(new_hi)

    def gauss_newton(self, x, iterations=60):
        """Minimum-norm Gauss-Newton steps x -= J^T (J J^T)^-1 F, vectorised over the rows of x."""
        x = x.copy()
        m = self.dim - 1
        for _ in range(iterations):
            f = self.np_f(*x.T).T                                  # (n, m)
            j = self.np_grad(*x.T).T.reshape(len(x), m, self.dim)  # (n, m, dim)
            jjt = np.einsum('nik,njk->nij', j, j)
            with np.errstate(all='ignore'):
                step = np.einsum('nik,ni->nk', j, np.linalg.solve(jjt + 1e-300 * np.eye(m), f[..., None])[..., 0])
            step = np.where(np.isfinite(step), step, 0.0)
            x -= step
        f = self.np_f(*x.T).T
        g = np.linalg.norm(self.np_grad(*x.T).T.reshape(len(x), m, self.dim), axis=2)
        with np.errstate(all='ignore'):
            residual = np.abs(f / np.maximum(g, 1e-300)).max(1)
        return x, residual

    def discover(self):
        lo, hi = self.subdivide()
        self.cells = len(lo)
        if not len(lo):
            raise ValueError('no point of the curve in the box')
        centres = (lo + hi) / 2
        self.h = float((hi - lo).max())
        x, residual = self.gauss_newton(centres)
        size = float(np.linalg.norm(self.box[:, 1] - self.box[:, 0]))
        inside = np.all((x >= self.box[:, 0] - 1e-12 * size) & (x <= self.box[:, 1] + 1e-12 * size), axis=1)
        near = np.linalg.norm(x - centres, axis=1) <= 2 * self.h * math.sqrt(self.dim)
        good = inside & near & (residual <= 1e-9 * self.h)
        self.samples = np.clip(x[good], self.box[:, 0], self.box[:, 1])
        self.tree = cKDTree(self.samples)
        self.scale = float(np.linalg.norm(self.samples.max(0) - self.samples.min(0))) if len(self.samples) else size
        self.singular_points = self.find_singular(lo, hi)
        self.endpoints = self.find_endpoints(lo, hi)

    def mp_solve(self, system, jacobian, x, fixed=None, iterations=80):
        """Gauss-Newton in mpmath on system(x) = 0 (square or overdetermined); `fixed` = (k, value)
        holds one coordinate. The point and the residual's size."""
        x = [mpf(c) for c in x]
        free = [k for k in range(self.dim) if fixed is None or k != fixed[0]]
        if fixed is not None:
            x[fixed[0]] = mpf(fixed[1])
        for _ in range(iterations):
            r = system(*x)
            jac = jacobian(*x)
            rows = len(r)
            a = mpmath.matrix([[jac[i * self.dim + k] for k in free] for i in range(rows)])
            normal = a.T * a
            # a tiny Levenberg-Marquardt shift keeps the step defined (the minimum-norm one) where
            # the system is singular: a continuum of solutions, such as a circle of minima
            shift = mpf(10) ** (5 - WORK_DIGITS) * max(max(abs(normal[i, i]) for i in range(len(free))), mpf(10) ** -30)
            try:
                step = mpmath.lu_solve(normal + shift * mpmath.eye(len(free)), a.T * mpmath.matrix(r))
            except ZeroDivisionError:
                break
            for i, k in enumerate(free):
                x[k] -= step[i]
            if max(abs(step[i]) for i in range(len(free))) <= mpf(10) ** (10 - WORK_DIGITS) * (1 + max(abs(c) for c in x)):
                break
        return x, max(abs(c) for c in system(*x))

    def find_singular(self, lo, hi):
        """Points where f_i = 0 and the tangent vanishes: Gauss-Newton from the cells whose
        enclosures of those expressions all contain zero."""
        env = {x: (lo[:, k], hi[:, k]) for k, x in enumerate(self.vars)}
        keep = np.ones(len(lo), dtype=bool)
        for e in self.singular_exprs:
            elo, ehi = enclose(e, env)
            keep &= (elo <= 0) & (ehi >= 0)
        out = []
        for c in ((lo[keep] + hi[keep]) / 2)[:2000]:
            if any(float(norm([a - b for a, b in zip(c, q)])) <= 4 * self.h for q in out):
                continue
            # a singular point is a degenerate root, where Gauss-Newton converges only linearly
            x, res = self.mp_solve(self.mp_singular, self.mp_singular_jac, c, iterations=600)
            if res <= mpf(10) ** (25 - WORK_DIGITS) * (1 + self.scale) ** 4 and self.in_box(x):
                if not any(norm([a - b for a, b in zip(x, q)]) <= mpf(10) ** -15 * (1 + self.scale) for q in out):
                    out.append(x)
        return out

    def in_box(self, x, slack=1e-12):
        size = float(np.linalg.norm(self.box[:, 1] - self.box[:, 0]))
        return all(self.box[k, 0] - slack * size <= float(x[k]) <= self.box[k, 1] + slack * size for k in range(self.dim))

    def find_endpoints(self, lo, hi):
        """Where the curve crosses a face of the box: f_i = 0 with that coordinate held, by
        Newton from the centres of the cells on the face. [(point, face name, k, side)]"""
        out = []
        names = ('x', 'y', 'z')
        for k in range(self.dim):
            for side, bound in ((0, self.box[k, 0]), (1, self.box[k, 1])):
                on_face = (lo[:, k] == bound) if side == 0 else (hi[:, k] == bound)
                for c in ((lo[on_face] + hi[on_face]) / 2):
                    x, res = self.mp_solve(self.mp_f, self.mp_grad, c, fixed=(k, bound))
                    if res > mpf(10) ** (25 - WORK_DIGITS) * (1 + self.scale) ** 2 or not self.in_box(x, 0):
                        continue
                    if any(norm([a - b for a, b in zip(x, q[0])]) <= mpf(10) ** -15 * (1 + self.scale) for q in out):
                        continue
                    out.append((x, 'box-face(%s=%s)' % (names[k], 'min' if side == 0 else 'max'), k, side))
        return out

    # --- one point
    def second_variation(self, x, p):
        """d^2/ds^2 |x(s) - p|^2 / 2 along the curve by arc length: 1 + (x - p) . x''."""
        t = [mpf(c) for c in self.tangent_at(x)]
        t = [c / norm(t) for c in t]
        grads = self.mp_grad(*x)
        hess = self.mp_hess(*x)
        m, n = self.dim - 1, self.dim
        g = [grads[i * n:(i + 1) * n] for i in range(m)]
        # x'' lies in the normal space span(g_i), with g_i . x'' = -t^T H_i t
        rhs = [-sum(t[a] * hess[i * n * n + a * n + b] * t[b] for a in range(n) for b in range(n)) for i in range(m)]
        gram = mpmath.matrix([[dot(g[i], g[j]) for j in range(m)] for i in range(m)])
        coef = mpmath.lu_solve(gram, mpmath.matrix(rhs))
        xpp = [sum(coef[i] * g[i][a] for i in range(m)) for a in range(n)]
        return 1 + dot([a - b for a, b in zip(x, p)], xpp)

    def tangent_at(self, x):
        g = self.mp_grad(*x)
        n = self.dim
        if n == 2:
            return [-g[1], g[0]]
        a, b = g[0:3], g[3:6]
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def project(self, p, candidates=60):
        pm = [mpf(c) for c in p]
        pa = np.asarray(p, dtype=float)
        d = np.linalg.norm(self.samples - pa, axis=1)
        radius = 3 * self.h * math.sqrt(self.dim)
        order = np.argsort(d, kind='stable')
        seeds = []
        for i in order:
            if len(seeds) >= candidates:
                break
            if all(d[j] >= d[i] for j in self.tree.query_ball_point(self.samples[i], radius)):
                if not any(np.linalg.norm(self.samples[i] - self.samples[j]) <= radius for j in seeds):
                    seeds.append(i)
        found = []
        tol = mpf(10) ** (25 - WORK_DIGITS)
        lag = lambda *x: self.mp_lagrange(*x, *pm)                      # noqa: E731
        lag_jac = lambda *x: self.mp_lagrange_jac(*x, *pm)              # noqa: E731
        for i in seeds:
            x, res = self.mp_solve(lag, lag_jac, self.samples[i])
            if res > tol * (1 + self.scale + norm(pm)) ** 4 or not self.in_box(x, 0):
                continue
            if norm(self.tangent_at(x)) <= mpf(10) ** -20 * (1 + self.scale):
                continue   # a singular point: listed below
            if self.second_variation(x, pm) < -mpf(10) ** -20:
                continue   # a maximum of the distance (0: a circle of minima around p's axis)
            found.append(Minimum('regular', x, pm))
        for s in self.singular_points:
            ds = norm([a - b for a, b in zip(s, pm)])
            around = self.tree.query_ball_point([float(c) for c in s], radius)
            if all(d[j] >= float(ds) * (1 - 1e-12) for j in around):
                found.append(Minimum('singular-point', s, pm))
        for x, name, k, side in self.endpoints:
            t = self.tangent_at(x)
            inward = t if (t[k] > 0) == (side == 0) else [-c for c in t]
            if t[k] == 0 or dot([a - b for a, b in zip(x, pm)], inward) >= -tol * (1 + self.scale + norm(pm)) ** 2:
                found.append(Minimum(name, x, pm))
        best = min(m.distance for m in found) if found else mpf('inf')
        rec = record(found, pm, self.scale)
        rec['params'] = None
        rec['verified'] = bool(len(d) and float(best) <= d.min() * (1 + 1e-12))
        return rec

    def info(self):
        return {
            'curve_bbox': [[float(a), float(b)] for a, b in zip(self.samples.min(0), self.samples.max(0))],
            'endpoints': [[float(c) for c in e[0]] for e in self.endpoints],
            'singular_points': [[float(c) for c in s] for s in self.singular_points],
            'samples': int(len(self.samples)), 'cells': int(self.cells), 'cell_size': self.h,
        }


# ---------------------------------------------------------------------------------------------
# geometries from the JSON shapes of tests/data/ and of the API
# ---------------------------------------------------------------------------------------------
def build(case, quick=False, grid=None, samples=None, resolution=None):
    """A geometry from a case object: {"kind", "formulas", "domain"|"box"} (tests/data/ files,
    tests/data/papers/public_cases.json), {"formulas", "domain": {"u", "v"}} (tests/data/surface_*.json)
    or {"type", "x", ..., "equations", "domain", "constants"} (the API's geometry)."""
    constants = case.get('constants') or {}
    kind = case.get('kind') or case.get('type')
    formulas = case.get('formulas') or {k: case[k] for k in ('x', 'y', 'z') if k in case}
    domain = case.get('domain') or case.get('box')
    if kind is None:
        kind = 'surface' if 'u' in domain else None
    factor = 4 if quick else 1
    options = case.get('reference_options') or case.get('oracle_options') or {}
    command = case.get('generated_by') or case.get('oracle_command') or ''
    if isinstance(command, str):
        for key in ('grid', 'samples', 'resolution', 'rel_res'):
            m = re.search(r'--%s[= ](\d+)' % key.replace('_', '-'), command)
            if m:
                options.setdefault(key, int(m.group(1)))
    if kind in ('surface', 'parametric_surface'):
        g = grid or options.get('grid', 201)
        g = g[0] if isinstance(g, list) else g
        return ParametricSurface([formulas['x'], formulas['y'], formulas['z']], [domain['u'], domain['v']],
                                 max(int(g) // factor, 21), constants)
    if kind in ('paramcurve', 'parametric_curve'):
        comps = [formulas[k] for k in ('x', 'y', 'z') if k in formulas]
        n = samples or options.get('samples', 20001)
        return ParametricCurve(comps, domain['t'], max(int(n) // factor, 501), constants)
    if kind in ('implicit2d', 'curve3d', 'curve3d_implicit', 'implicit_curve'):
        eqs = case.get('equations') or [formulas[k] for k in sorted(formulas)]
        names = ('x', 'y', 'z')[:len(eqs) + 1]
        r = resolution or options.get('resolution') or max(options.get('rel_res', 0), 1000)
        return ImplicitCurve(eqs, [domain[n] for n in names], max(int(r) // factor, 100), constants)
    raise ValueError('unknown geometry kind %r' % kind)


def surface_output(args, geometry, points, command):
    formulas = {'x': args.x, 'y': args.y, 'z': args.z}
    return {'id': args.id or 'surface', 'title': args.title or '', 'formulas': formulas,
            'domain': {'u': list(args.u), 'v': list(args.v)}, 'generated_by': command,
            'points': [{'p': list(p), 'oracle': geometry.project(p)} for p in points]}


def curve_output(args, geometry, kind, formulas, domain, points, command):
    case = {'id': args.id or kind, 'kind': kind, 'formulas': formulas, 'domain': domain,
            'generated_by': command, 'points': []}
    for p in points:
        rec = geometry.project(p)
        case['points'].append(dict({'p': list(p)}, **rec))
    if isinstance(geometry, ImplicitCurve):
        case['curve_info'] = geometry.info()
    return case


# ---------------------------------------------------------------------------------------------
# check: recompute a data file
# ---------------------------------------------------------------------------------------------
def cases_of(data):
    if 'cases' in data:
        return data['cases']
    return [data]


def reference_of(point):
    return point['oracle'] if 'oracle' in point else point


def close_distance(a, b, scale):
    """Whether two stored distances agree, and their relative difference: to the digits of their
    strings less 5 when both have them (relative, and absolute times the object's size for a
    point on the object), else to 1e-14."""
    if 'distance_str' in a and 'distance_str' in b:
        x, y = mpf(a['distance_str']), mpf(b['distance_str'])
        digits = min(len(re.sub(r'[^0-9]', '', s['distance_str'].split('e')[0]).lstrip('0')) for s in (a, b))
        tol = mpf(10) ** -(min(digits, OUT_DIGITS) - 5)
    else:
        x, y, tol = mpf(a['distance']), mpf(b['distance']), mpf(10) ** -14
    if 'singular-point' in (a.get('type'), b.get('type')):
        tol = max(tol, mpf(10) ** -20)   # the stored singular points are good to about 1e-24
    diff = abs(x - y)
    relative = 0.0 if max(abs(x), abs(y)) <= 1e-20 * max(1, scale) else float(diff / max(abs(x), abs(y)))
    return diff <= tol * (max(abs(x), abs(y)) + max(1, scale)), relative


def check(args):
    with open(args.file) as f:
        data = json.load(f)
    passed = failed = warned = 0
    worst = 0.0
    for case in cases_of(data):
        cid = case.get('id', '?')
        if args.case and cid not in args.case:
            continue
        if 'points' not in case:
            continue
        geometry = build(case, quick=args.quick, grid=args.grid, samples=args.samples, resolution=args.resolution)
        if args.verbose:
            print('%s: %s' % (cid, geometry.kind), flush=True)
        if isinstance(geometry, ImplicitCurve) and 'curve_info' in case and not args.quick:
            for key, mine in (('singular_points', geometry.singular_points), ('endpoints', [e[0] for e in geometry.endpoints])):
                theirs = case['curve_info'].get(key, [])
                unmatched = [q for q in theirs if not any(float(norm([mpf(a) - b for a, b in zip(q, m)])) <= 1e-9 * (1 + geometry.scale) for m in mine)]
                if unmatched or len(theirs) != len(mine):
                    print('WARN %s curve_info.%s: stored %d, found %d' % (cid, key, len(theirs), len(mine)))
                    warned += 1
        points = case['points'][:args.max_points] if args.max_points else case['points']
        for i, point in enumerate(points):
            stored = reference_of(point)
            try:
                mine = geometry.project(point['p'])
            except (RuntimeError, ValueError, ZeroDivisionError) as e:
                failed += 1
                print('FAIL %s point %d p=%s: %s' % (cid, i, point['p'], e), flush=True)
                continue
            problems = []
            ok, rel = close_distance(stored, mine, geometry.scale)
            worst = max(worst, rel) if ok else worst
            if not ok:
                problems.append('distance %s, recomputed %s (relative %.2g)' % (
                    stored.get('distance_str', stored['distance']), mine['distance_str'], rel))
            elif not stored.get('ambiguous') and not mine['ambiguous']:
                gap = max(abs(a - b) for a, b in zip(stored['foot'], mine['foot']))
                if gap > 1e-9 * max(1.0, max(abs(c) for c in mine['foot'])):
                    problems.append('foot %s, recomputed %s' % (stored['foot'], mine['foot']))
                # a singular point where the Lagrange conditions hold as well (a tacnode) may be
                # called either; where several parameters give the foot, so may its location
                either = 'singular-point' in (stored['type'], mine['type'])
                if not (either or stored.get('params_nonunique') or mine.get('params_nonunique')) \
                        and stored['type'] != mine['type']:
                    problems.append('type %s, recomputed %s' % (stored['type'], mine['type']))
            if 'local_minima' in stored and not args.quick:
                missing = [m for m in stored['local_minima'] if not any(
                    abs(m['distance'] - o['distance']) <= 1e-9 * m['distance'] + 1e-20 * max(1, geometry.scale)
                    for o in mine['local_minima'])]
                if missing and len(mine['local_minima']) < MAX_LISTED:
                    print('WARN %s point %d: stored local minima not found: %s' % (
                        cid, i, ', '.join('%s d=%.12g' % (m['type'], m['distance']) for m in missing)))
                    warned += 1
            if problems:
                failed += 1
                print('FAIL %s point %d p=%s: %s' % (cid, i, point['p'], '; '.join(problems)), flush=True)
            else:
                passed += 1
                if args.verbose:
                    print('ok   %s point %d d=%s %s' % (cid, i, mine['distance_str'][:20], mine['type']), flush=True)
    print('largest relative distance difference of the agreeing points: %.2g; %d warnings' % (worst, warned))
    print('%d passed, %d failed' % (passed, failed))
    return 0 if failed == 0 and passed > 0 else 1


# ---------------------------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------------------------
def numbers(s):
    return [float(c) for c in s.split(',')]


def pairs(values, count):
    if len(values) != 2 * count:
        raise argparse.ArgumentTypeError('expected %d numbers' % (2 * count))
    return [values[2 * i:2 * i + 2] for i in range(count)]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    sub = ap.add_subparsers(dest='command', required=True)

    def generating(name):
        s = sub.add_parser(name)
        s.add_argument('--point', '-p', action='append', type=numbers, required=True)
        s.add_argument('--id')
        s.add_argument('--title')
        s.add_argument('--out')
        return s
    s = generating('surface')
    for k in ('x', 'y', 'z'):
        s.add_argument('--' + k, required=True)
    s.add_argument('--u', type=numbers, required=True)
    s.add_argument('--v', type=numbers, required=True)
    s.add_argument('--grid', type=int, default=201)
    c = generating('paramcurve')
    c.add_argument('--x', required=True)
    c.add_argument('--y', required=True)
    c.add_argument('--z')
    c.add_argument('--t', type=numbers, required=True)
    c.add_argument('--samples', type=int, default=20001)
    i2 = generating('implicit2d')
    i2.add_argument('--f', required=True)
    i2.add_argument('--box', type=numbers, required=True)
    i2.add_argument('--resolution', type=int, default=1000)
    i3 = generating('curve3d')
    i3.add_argument('--f1', required=True)
    i3.add_argument('--f2', required=True)
    i3.add_argument('--box', type=numbers, required=True)
    i3.add_argument('--resolution', type=int, default=1000)
    g = generating('geometry')
    g.add_argument('geometry', help='a JSON file with the geometry as the API takes it (- for stdin)')
    g.add_argument('--grid', type=int)
    g.add_argument('--samples', type=int)
    g.add_argument('--resolution', type=int)
    ch = sub.add_parser('check')
    ch.add_argument('file')
    ch.add_argument('--case', action='append')
    ch.add_argument('--max-points', type=int)
    ch.add_argument('--quick', action='store_true')
    ch.add_argument('--grid', type=int)
    ch.add_argument('--samples', type=int)
    ch.add_argument('--resolution', type=int)
    ch.add_argument('-v', '--verbose', action='store_true')
    args = ap.parse_args(argv)
    if args.command == 'check':
        return check(args)

    command = 'tests/tools/gen_reference.py ' + ' '.join(shlex.quote(a) for a in argv if not a.startswith('--out'))
    points = args.point
    if args.command == 'surface':
        geometry = ParametricSurface([args.x, args.y, args.z], [args.u, args.v], args.grid)
        out = surface_output(args, geometry, points, command)
    elif args.command == 'paramcurve':
        comps = {'x': args.x, 'y': args.y}
        if args.z:
            comps['z'] = args.z
        geometry = ParametricCurve(list(comps.values()), args.t, args.samples)
        out = curve_output(args, geometry, 'paramcurve', comps, {'t': args.t}, points, command)
    elif args.command in ('implicit2d', 'curve3d'):
        dim = 2 if args.command == 'implicit2d' else 3
        eqs = {'f': args.f} if dim == 2 else {'f1': args.f1, 'f2': args.f2}
        box = pairs(args.box, dim)
        geometry = ImplicitCurve(list(eqs.values()), box, args.resolution)
        out = curve_output(args, geometry, args.command, eqs, dict(zip('xyz', box)), points, command)
    else:
        with (sys.stdin if args.geometry == '-' else open(args.geometry)) as f:
            definition = json.load(f)
        geometry = build(definition, grid=args.grid, samples=args.samples, resolution=args.resolution)
        if isinstance(geometry, ParametricSurface):
            out = {'id': args.id or 'surface', 'title': args.title or '', 'geometry': definition,
                   'generated_by': command,
                   'points': [{'p': list(p), 'oracle': geometry.project(p)} for p in points]}
        else:
            out = curve_output(args, geometry, geometry.kind, definition.get('equations') or
                               {k: definition[k] for k in ('x', 'y', 'z') if k in definition},
                               definition['domain'], points, command)
    if args.title and 'title' not in out:
        out['title'] = args.title
    text_out = json.dumps(out, indent=1)
    if args.out:
        with open(args.out, 'w') as f:
            f.write(text_out + '\n')
    else:
        print(text_out)
    return 0


if __name__ == '__main__':
    sys.exit(main())
