#!/usr/bin/python3
"""Writes the point sets of the Open CASCADE comparison with their references: bench/occt/data/<NAME>.json
for every surface of bench/occt/surfaces.json. Deterministic (numpy's PCG64, seed 20261201), so a
rerun rewrites the same files. Run with Debian's python3-numpy, python3-scipy, python3-sympy,
python3-mpmath (it takes some minutes: every reference is a 50-digit global search):

    bench/occt/make_data.py [--box N] [--near N] [NAME ...]      (default 300 and 150, all surfaces)

Per surface:
  box    N points uniform in the box centred on the surface's bounding box with twice its extent
         (most of their nearest points are on an edge or a corner);
  near   N points s(u,v) + t n(u,v), (u,v) uniform in the inner 90% of the domain, n the unit
         normal, |t| <= 1% of the bounding box's diagonal (mostly interior nearest points);
  references  the global nearest point of each (tests/tools/gen_reference.py: distance to 50
         digits, parameters, where it lies);
  bezier  for a polynomial surface, its exact Bernstein form on the domain ([Farin], README's
         References: b_kl = sum over i <= k, j <= l of C(k,i)/C(n,i) C(l,j)/C(m,j) a_ij, a_ij
         the power coefficients in the affine parameters s, t in [0,1]), every pole an exact
         rational rounded once to a double.
A B-spline surface (surfaces.json: "bspline" names a geometry of
tests/tools/gen_nurbs_projection_refs.py) is written as its definition (`bspline`, the
bspline_surface JSON), its point sets drawn the same way (the bounding box from a 201 x 201 grid
of surface points, the normal from the generator's derivatives) and its references from that
generator (50-digit global search; the sphere's cross-checked against |p| - 1).
"""
import argparse
import json
import os
import sys

import numpy as np
import sympy as sp

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', '..', 'tests', 'tools'))
import gen_nurbs_projection_refs as nurbs  # noqa: E402
import gen_reference  # noqa: E402

SEED = 20261201


def bounding_box(surface):
    flat = surface.nodes.reshape(3, -1)
    return flat.min(1), flat.max(1)


def bezier(formulas, domain):
    """The Bernstein poles [k][l] = [x, y, z] of a polynomial surface over its domain."""
    u, v = gen_reference.SYMBOLS['u'], gen_reference.SYMBOLS['v']
    s, t = sp.symbols('s t')
    (u0, u1), (v0, v1) = [[gen_reference.exact_double(c) for c in domain[k]] for k in ('u', 'v')]
    polys = []
    for k in ('x', 'y', 'z'):
        e = gen_reference.parse_formula(formulas[k], ('u', 'v'))
        polys.append(sp.Poly(sp.expand(e.subs({u: u0 + (u1 - u0) * s, v: v0 + (v1 - v0) * t}, simultaneous=True)), s, t))
    n = max(p.degree(s) for p in polys)
    m = max(p.degree(t) for p in polys)
    poles = [[[0.0] * 3 for _ in range(m + 1)] for _ in range(n + 1)]
    for c, p in enumerate(polys):
        a = dict(p.terms())
        for k in range(n + 1):
            for l in range(m + 1):
                b = sum((sp.binomial(k, i) / sp.binomial(n, i) * sp.binomial(l, j) / sp.binomial(m, j) * coef
                         for (i, j), coef in a.items() if i <= k and j <= l), sp.Integer(0))
                poles[k][l][c] = float(b)
        # the Bernstein form equals the polynomial: at a few rational points, exactly
        for ss, tt in ((sp.Rational(1, 3), sp.Rational(2, 7)), (sp.Rational(5, 6), sp.Rational(1, 9))):
            exact = p.as_expr().subs({s: ss, t: tt})
            bern = sum(sp.binomial(n, k) * ss ** k * (1 - ss) ** (n - k) * sp.binomial(m, l) * tt ** l * (1 - tt) ** (m - l)
                       * sp.Rational(poles[k][l][c]) for k in range(n + 1) for l in range(m + 1))
            assert abs(float(bern - exact)) <= 1e-12 * max(1.0, abs(float(exact))), (formulas, c)
    return {'degrees': [n, m], 'poles': poles}


def point_sets(surface, spec, box_count, near_count, rng):
    lo, hi = bounding_box(surface)
    centre, extent = (lo + hi) / 2, hi - lo
    box = centre + extent * rng.uniform(-1.0, 1.0, size=(box_count, 3))
    (u0, u1), (v0, v1) = spec['domain']['u'], spec['domain']['v']
    diagonal = float(np.linalg.norm(extent))
    near = []
    while len(near) < near_count:
        a = u0 + (u1 - u0) * (0.05 + 0.9 * rng.uniform())
        b = v0 + (v1 - v0) * (0.05 + 0.9 * rng.uniform())
        tangents = surface.tangents(a, b)
        normal = np.cross(tangents[0:3], tangents[3:6])
        length = np.linalg.norm(normal)
        if length < 1e-9:
            continue
        near.append(surface.points(a, b) + rng.uniform(-0.01, 0.01) * diagonal * normal / length)
    return box.tolist(), [list(map(float, p)) for p in near]


class BSplineSurface:
    """A bspline_surface of the NURBS generator with the interface point_sets and reference use."""

    def __init__(self, name):
        found = [(d, cf) for n, d, cf, _ in nurbs.definitions() if n == name]
        if not found:
            raise SystemExit('make_data: no geometry %r in tests/tools/gen_nurbs_projection_refs.py' % name)
        self.definition, self.closed_form = found[0]
        self.geom = nurbs.build(self.definition)
        self.searcher = nurbs.Searcher(self.geom, nurbs.SAMPLES['bspline_surface'])
        (u0, u1), (v0, v1) = [(float(d.lo), float(d.hi)) for d in self.geom.dirs]
        self.domain = {'u': [u0, u1], 'v': [v0, v1]}
        us, vs = np.linspace(u0, u1, 201), np.linspace(v0, v1, 201)
        self.nodes = np.array([[self.geom.point_float(a, b) for b in vs] for a in us]).transpose(2, 0, 1)

    def points(self, a, b):
        return np.array(self.geom.point_float(a, b))

    def tangents(self, a, b):
        _, (su, sv), _ = self.geom.jet_float(a, b)
        return np.array(su + sv)

    def project(self, p):
        r = nurbs.project(self.geom, self.searcher, [float(c) for c in p], self.closed_form)
        return {'distance': r['distance'], 'distance_str': r['distance_str'], 'params': r['params'],
                'type': r['location']}


def reference(surface, p):
    r = surface.project(p)
    where = 'interior' if r['type'] == 'interior' else r['type'].split('(')[0]
    return {'distance': r['distance'], 'distance_str': r['distance_str'], 'params': r['params'], 'where': where}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--box', type=int, default=300)
    ap.add_argument('--near', type=int, default=150)
    ap.add_argument('names', nargs='*')
    args = ap.parse_args()
    with open(os.path.join(HERE, 'surfaces.json')) as f:
        specs = json.load(f)['surfaces']
    rng = np.random.default_rng(SEED)
    for spec in specs:
        # every surface draws from the one stream in file order, so that a subset reproduces too
        if 'bspline' in spec:
            surface = BSplineSurface(spec['bspline'])
            spec = dict(spec, domain=surface.domain)
        else:
            surface = gen_reference.ParametricSurface([spec['formulas'][k] for k in ('x', 'y', 'z')],
                                                      [spec['domain']['u'], spec['domain']['v']], 201)
        box, near = point_sets(surface, spec, args.box, args.near, rng)
        if args.names and spec['name'] not in args.names:
            continue
        out = {'name': spec['name']}
        if 'bspline' in spec:
            out['bspline'] = surface.definition
        else:
            out['formulas'] = spec['formulas']
        out['domain'] = spec['domain']
        out['generated_by'] = 'bench/occt/make_data.py --box %d --near %d (seed %d)' % (args.box, args.near, SEED)
        if spec.get('occt') == 'bezier':
            out['bezier'] = bezier(spec['formulas'], spec['domain'])
        if spec.get('occt') == 'torus':
            out['torus'] = spec['torus']
        out['sets'] = {}
        for name, points in (('box', box), ('near', near)):
            refs = []
            for i, p in enumerate(points):
                refs.append(reference(surface, p))
                if (i + 1) % 50 == 0:
                    print('%s %s: %d/%d' % (spec['name'], name, i + 1, len(points)), flush=True)
            out['sets'][name] = {'points': points, 'references': refs}
        path = os.path.join(HERE, 'data', spec['name'] + '.json')
        with open(path, 'w') as f:
            json.dump(out, f, indent=1)
            f.write('\n')
        print('%s: %d box + %d near points -> %s' % (spec['name'], len(box), len(near), os.path.relpath(path)), flush=True)


if __name__ == '__main__':
    main()
