#!/usr/bin/env python3
"""Chapter 3, Pursey's parabola, re-derived with SymPy (run by CTest, label book).

Normalised span: t in [0, 1], s(t) = t / (r - (r - 1) t) (eq. 3.5), parabola through
s(0) = 0, s(1/2) = 1/(1 + r), s(1) = 1. Checks the slopes at both ends, when the parabola
is monotonic, where it turns and how far it overshoots (eq. pursey-slopes and
pursey-overshoot), and the error formula eq. 3.11. Exits non-zero on any mismatch.
"""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import failures, same, finish  # noqa: E402

r, t = sp.symbols("r t", positive=True)
s = t / (r - (r - 1) * t)
A, B = sp.symbols("A B")
q = A * t**2 + B * t
coefficients = sp.solve([q.subs(t, sp.Rational(1, 2)) - 1 / (1 + r), q.subs(t, 1) - 1],
                        [A, B])
q = q.subs(coefficients)


slope = sp.diff(q, t)
same("slope at t = 0", slope.subs(t, 0), (3 - r) / (1 + r))
same("slope at t = 1", slope.subs(t, 1), (3 * r - 1) / (1 + r))
same("quadratic error (eq:quadratic-error)", q - s,
     2 * (r - 1)**2 * t * (t - sp.Rational(1, 2)) * (1 - t) / ((r + 1) * (r - (r - 1) * t)))
# The same from divided differences, as the text argues: f = 1 / (r - (r - 1) t) has
# f[t0..tm] = (r - 1)^m / prod(r - (r - 1) ti), s = (r f - 1) / (r - 1), and s - q is
# t (t - 1/2)(t - 1) times s[0, 1/2, 1, t] = r / (r - 1) f[0, 1/2, 1, t].
f = 1 / (r - (r - 1) * t)
same("s from f", s, (r * f - 1) / (r - 1))
u_ = sp.symbols("u")
points = [sp.Integer(0), sp.Rational(1, 2), sp.Integer(1), u_]


def divided(values, nodes):
    if len(nodes) == 1:
        return values[0]
    return (divided(values[1:], nodes[1:]) - divided(values[:-1], nodes[:-1])) \
        / (nodes[-1] - nodes[0])


f_at = [f.subs(t, x) for x in points]
same("divided difference of f", divided(f_at, points),
     (r - 1)**3 / sp.prod([r - (r - 1) * x for x in points]))
same("error from the divided difference", (s - q).subs(t, u_),
     u_ * (u_ - sp.Rational(1, 2)) * (u_ - 1) * r / (r - 1) * divided(f_at, points))
turn = sp.solve(sp.Eq(slope, 0), t)[0]
same("turning point", turn, (r - 3) / (4 * (r - 1)))
same("value at the turning point", q.subs(t, turn), -(r - 3)**2 / (8 * (r - 1) * (r + 1)))
# The slope is linear in t, so the parabola is monotonic on [0, 1] exactly when both end
# slopes have one sign: (3 - r) >= 0 and (3 r - 1) >= 0.
monotonic = sp.solve_univariate_inequality((3 - r) * (3 * r - 1) >= 0, r, relational=False)
if monotonic != sp.Interval(sp.Rational(1, 3), 3):
    failures.append(f"monotonic set {monotonic} != [1/3, 3]")
same("figure 3.3: r = 4, 64 texels", 64 * q.subs(r, 4).subs(t, turn.subs(r, 4)),
     sp.Rational(-8, 15))
same("overshoot tends to 1/8", sp.limit((r - 3)**2 / (8 * (r - 1) * (r + 1)), r, sp.oo),
     sp.Rational(1, 8))
finish("ch03_pursey.py")
