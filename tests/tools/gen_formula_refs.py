#!/usr/bin/python3
"""Reference values for tests/core/formula/program_test.cpp: value and all partial derivatives up to
third order of muparser-syntax formulas, computed symbolically with sympy and evaluated with 40
digits. Run with Debian's python3-sympy:  /usr/bin/python3 tests/tools/gen_formula_refs.py
It rewrites tests/data/formula_refs.json."""
import itertools, json, os
import sympy as sp

x, y = sp.symbols('x y')
R = sp.Rational(5, 2)
CASES = [
    # (muparser formula, sympy expression, constants, points)
    ("x^2*y^3/(1+x*y)", x**2*y**3/(1+x*y), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("sin(x*y)+cos(x-y)*tan(0.3*x)", sp.sin(x*y)+sp.cos(x-y)*sp.tan(sp.Rational(3, 10)*x), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("asin(0.3*x*y)+acos(0.2*x-0.1*y)+atan(x/y)",
     sp.asin(sp.Rational(3, 10)*x*y)+sp.acos(sp.Rational(1, 5)*x-sp.Rational(1, 10)*y)+sp.atan(x/y), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("sinh(0.5*x)*cosh(y)-tanh(x*y)", sp.sinh(x/2)*sp.cosh(y)-sp.tanh(x*y), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("asinh(x*y)+acosh(2+x^2)+atanh(0.3*y)", sp.asinh(x*y)+sp.acosh(2+x**2)+sp.atanh(sp.Rational(3, 10)*y), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("exp(x-y)*ln(x^2+y^2)+log2(1+x^2)-log10(2+y)+log(3+x)",
     sp.exp(x-y)*sp.log(x**2+y**2)+sp.log(1+x**2, 2)-sp.log(2+y, 10)+sp.log(3+x), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("sqrt(x^2+y^2+1)/(x+3)", sp.sqrt(x**2+y**2+1)/(x+3), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("x^y", x**y, {}, [(0.7, 1.3), (1.6, 0.45)]),
    # abs, sign, min and max written as the branch that holds at the point (x < y at both points)
    ("(x-2*y)^6 - (x*y)^(-3) + abs(x-y)*y + sign(x)*y^2", (x-2*y)**6-(x*y)**(-3)+(y-x)*y+y**2, {}, [(0.7, 1.3)]),
    ("(x-2*y)^6 - (x*y)^(-3) + abs(x-y)*y + sign(x)*y^2", (x-2*y)**6-(x*y)**(-3)+(y-x)*y-y**2, {}, [(-1.1, 0.4)]),
    ("min(x*y, x+y, 5) + max(x^2, y)", x*y+y, {}, [(0.7, 1.3)]),
    ("min(x*y, x+y, 5) + max(x^2, y)", x*y+x**2, {}, [(1.6, 0.45)]),
    ("-x^2 + 2^3^2*y - -y", -x**2+512*y+y, {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("_pi*x + _e*y + R*x*y", sp.pi*x+sp.E*y+R*x*y, {"R": 2.5}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("x > y ? x^2*y : y^3 - x", sp.Piecewise((x**2*y, x > y), (y**3-x, True)), {}, [(0.7, 1.3), (1.6, 0.45)]),
    ("x^0.5*y^1.5 + (x*y)^(1/3)", sp.sqrt(x)*y**sp.Rational(3, 2)+(x*y)**sp.Rational(1, 3), {}, [(0.7, 1.3), (1.6, 0.45)]),
    ("(u_shift+x)^3", (sp.Rational(-3, 2)+x)**3, {"u_shift": -1.5}, [(0.0, 0.5), (0.2, 1.0)]),
    # sums of monomials (evaluated term by term, core/formula/polynomial.cpp): the surfaces S2 and
    # S3's first component, signs folded through -( ), k - ( ) and a - (b + c), constants divided
    ("x^4*y^3+x*y+x", x**4*y**3+x*y+x, {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("x^6+x^5*y+y^6-x^2*y^3+x*y^4-y^5+x^4+x^3*y+y^4+x^3-x*y^2+y^3+x*y+y^2+1",
     x**6+x**5*y+y**6-x**2*y**3+x*y**4-y**5+x**4+x**3*y+y**4+x**3-x*y**2+y**3+x*y+y**2+1, {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("1 - (x^2*y - 3*x) - y^3/4 + x*(-y)^2*R", 1-(x**2*y-3*x)-y**3/4+x*y**2*R, {"R": 2.5}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("-(x^3 - 2*y) + 4 - x*(y^2 - x^5)", -(x**3-2*y)+4-x*(y**2-x**5), {}, [(0.7, 1.3), (-1.1, 0.4)]),
    ("(2*x*y^2)^3 - x^7 + 5", 8*x**3*y**6-x**7+5, {}, [(0.7, 1.3), (-1.1, 0.4)]),
]

def num(e, pt):
    v = sp.N(e.subs({x: sp.Float(pt[0], 40), y: sp.Float(pt[1], 40)}), 40)
    return float(v)

out = []
for text, expr, consts, pts in CASES:
    for pt in pts:
        rec = {"formula": text, "constants": consts, "point": list(pt), "value": num(expr, pt)}
        rec["gradient"] = [num(sp.diff(expr, v), pt) for v in (x, y)]
        rec["hessian"] = [[num(sp.diff(expr, a, b), pt) for b in (x, y)] for a in (x, y)]
        rec["third"] = [[[num(sp.diff(expr, a, b, c), pt) for c in (x, y)] for b in (x, y)] for a in (x, y)]
        out.append(rec)
path = os.path.join(os.path.dirname(__file__), '..', 'data', 'formula_refs.json')
with open(path, 'w') as f:
    json.dump({"generated_by": "tests/tools/gen_formula_refs.py (sympy, 40 digits)", "cases": out}, f, indent=1)
print(len(out), "reference points written to", os.path.normpath(path))
