#!/usr/bin/env python3
"""Chapter 7's bound on the affine mapper over a whole triangle (eq:scene-triangle-bound),
re-derived with SymPy (run by CTest, label book): the error as a sum over the corners,
the total variation of the screen barycentrics against the perspective-correct ones, its
largest value over every point and every depth with w_max / w_min = r, and exact rational
checks of that maximum and of the bound's tightness.
Exits non-zero on any mismatch."""
import itertools
import pathlib
import sys
from fractions import Fraction

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402

# The affine and the perspective-correct value at a point of screen barycentrics l_i:
# sum l_i u_i and sum l'_i u_i, l'_i = (l_i / w_i) / sum_j (l_j / w_j). Both weights sum
# to 1, so their difference is sum (l_i - l'_i)(u_i - c) for any c.
l0, l1 = sp.symbols("lambda0 lambda1", nonnegative=True)
l = [l0, l1, 1 - l0 - l1]
w = sp.symbols("w0:3", positive=True)
u = sp.symbols("u0:3", real=True)
c = sp.Symbol("c", real=True)
Q = sum(li / wi for li, wi in zip(l, w))
lp = [li / wi / Q for li, wi in zip(l, w)]
same("perspective weights sum to 1", sp.together(sum(lp)), 1)
same("error as a sum over corners",
     sum(li * ui for li, ui in zip(l, u)) - sum(pi * ui for pi, ui in zip(lp, u)),
     sum((li - pi) * (ui - c) for li, pi, ui in zip(l, lp, u)))

# The total variation T = sum |l_i - l'_i| is twice the gain of the corners whose l'_i
# exceeds l_i (those with 1/w_i > Q, the near ones): with m their screen mass, a their
# sum of l_i / w_i and b the others', T = 2 (a / (a + b) - m). a / (a + b) grows with a and
# falls with b, and a <= m / w_min, b >= (1 - m) / w_max: so T / 2 <= g(m), r = w_max/w_min.
a, b = sp.symbols("a b", positive=True)
holds("a/(a+b) grows with a", sp.simplify(sp.diff(a / (a + b), a) - b / (a + b) ** 2) == 0)
holds("a/(a+b) falls with b", sp.simplify(sp.diff(a / (a + b), b) + a / (a + b) ** 2) == 0)
m = sp.Symbol("m", nonnegative=True)
r, s = sp.symbols("r s", positive=True)  # s = sqrt r
wmin = sp.Symbol("w_min", positive=True)
g = sp.simplify((m / wmin) / (m / wmin + (1 - m) / (r * wmin)) - m)
# g is chapter 3's affine error (eq:affine-error) read from the far end, e(1 - m):
t = 1 - m
same("g is e(1 - m)", g, (r - 1) * t * (1 - t) / (r - (r - 1) * t))
# Its largest value, at m = 1 / (sqrt r + 1), is (sqrt r - 1) / (sqrt r + 1):
gs = g.subs(r, s**2)
same("g' vanishes at m = 1/(s+1)", sp.diff(gs, m).subs(m, 1 / (s + 1)), 0)
same("g(1/(s+1))", gs.subs(m, 1 / (s + 1)), (s - 1) / (s + 1))
same("g is concave", sp.factor(sp.diff(gs, m, 2)), -2 * s**2 * (s**2 - 1) / ((s**2 - 1) * m + 1) ** 3)
# So |affine - exact| <= max_i |u_i - c| T <= (u_max - u_min)/2 * 2 (s - 1)/(s + 1) with c
# the mid-range: eq:scene-triangle-bound, chapter 3's eq:affine-bound with the triangle's
# extent and depth ratio.


def total_variation(lam, ws):
    q = sum(li / wi for li, wi in zip(lam, ws))
    return sum(abs(li - li / wi / q) for li, wi in zip(lam, ws))


def within(T, ratio):
    """T <= 2 (sqrt r - 1)/(sqrt r + 1) in rationals: T/2 = h <= (s-1)/(s+1) iff
    s >= (1 + h)/(1 - h) iff r >= ((1 + h)/(1 - h))^2 (h < 1)."""
    h = T / 2
    return h < 1 and ratio >= ((1 + h) / (1 - h)) ** 2


# Exact rational checks: every point of a grid of barycentrics (denominator 24) and every
# triple of depths from {1, 2, 3, 4, 9}: the total variation never exceeds the maximum.
grid = [Fraction(k, 24) for k in range(25)]
depths = [Fraction(d) for d in (1, 2, 3, 4, 9)]
checked = 0
for ws in itertools.product(depths, repeat=3):
    ratio = max(ws) / min(ws)
    for i, j in itertools.product(range(25), repeat=2):
        if i + j > 24:
            continue
        lam = (grid[i], grid[j], 1 - grid[i] - grid[j])
        holds(f"total variation at {lam}, {ws}", within(total_variation(lam, ws), ratio))
        checked += 1
holds("grid checked", checked == 125 * 325)
# ... and reaches it: r = s^2 with s rational, on the edge from a w_min corner to a w_max
# corner at screen mass m = 1/(s + 1) on the near one, with u 0 there and u = D far.
for sq in (Fraction(2), Fraction(3), Fraction(5, 2), Fraction(7)):
    mass = 1 / (sq + 1)
    ws = (Fraction(1), sq * sq, Fraction(1))
    lam = (mass, 1 - mass, Fraction(0))
    holds(f"maximum reached at s = {sq}",
          total_variation(lam, ws) == 2 * (sq - 1) / (sq + 1))
    D = Fraction(5)
    us = (Fraction(0), D, Fraction(0))
    q = sum(li / wi for li, wi in zip(lam, ws))
    affine = sum(li * ui for li, ui in zip(lam, us))
    exact = sum(li * ui / wi for li, ui, wi in zip(lam, us, ws)) / q
    holds(f"error bound reached at s = {sq}", affine - exact == D * (sq - 1) / (sq + 1))

finish("ch07_triangle_bound")
