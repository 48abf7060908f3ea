#!/usr/bin/env python3
"""The course's variant exercises of chapters 1 to 3, re-derived with SymPy (run by CTest,
label book). Each answer is the one the exercise region's solution computes and the
teacher's edition derives; none is printed in a chapter. Exits non-zero on any mismatch.

- ch01-gradient-3d: the gradient of c over a triangle in space, in the triangle's plane:
  g = (dc2 (e3 x n) + dc3 (n x e2)) / |n|^2 with n = e2 x e3.
- ch01-prestep-up: walking up from the lower vertex with a bottom-left rule, the first row
  is floor(y - 1/2), reached by a step of (row + 1/2 - y), in (-1, 0].
- ch02-block-area: over the squares of an n_x x n_y block, the edge value is largest at
  w + max(-s_x/2, (n_x - 1/2) s_x) + max(-s_y/2, (n_y - 1/2) s_y) (w at the top-left centre).
- ch03-pixel-of-u: the pixel t at which the exact mapper reaches u:
  t = (u q0 - p0) / (p_t - u q_t).
- ch03-quarter-point: the parabola through the exact values at t = 0, n/4 and n:
  a = (4 D - k) / (3 n^2), b = (k - D) / (3 n), k = 16 D w0 / (w0 + 3 w2).
"""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import failures, holds, same, finish  # noqa: E402

# --- ch01-gradient-3d -----------------------------------------------------------------
P = [sp.Matrix(sp.symbols(f"x{i} y{i} z{i}")) for i in range(3)]
c0, c1, c2 = sp.symbols("c0 c1 c2")
e2, e3 = P[1] - P[0], P[2] - P[0]
n = e2.cross(e3)
g = ((c1 - c0) * e3.cross(n) + (c2 - c0) * n.cross(e2)) / n.dot(n)
same("3d gradient along e2", g.dot(e2), c1 - c0)
same("3d gradient along e3", g.dot(e3), c2 - c0)
same("3d gradient in the plane", g.dot(n), 0)
# In the plane z = 0 it is chapter 1's closed form (@eq:closed-form, vertices 1..3 -> 0..2).
flat = {P[0][2]: 0, P[1][2]: 0, P[2][2]: 0}
x0, y0, _ = P[0]
x1, y1, _ = P[1]
x2, y2, _ = P[2]
area2 = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
same("3d gradient in z = 0, x", g[0].subs(flat),
     ((c1 - c0) * (y2 - y0) - (c2 - c0) * (y1 - y0)) / area2)
same("3d gradient in z = 0, y", g[1].subs(flat),
     ((c2 - c0) * (x1 - x0) - (c1 - c0) * (x2 - x0)) / area2)
same("3d gradient in z = 0, z", g[2].subs(flat), 0)
# The plane through the three values: c0 + g . (p - p0) equals c_i at every vertex.
for i, ci in enumerate([c0, c1, c2]):
    same(f"3d plane at vertex {i}", c0 + g.dot(P[i] - P[0]), ci)

# --- ch01-prestep-up ------------------------------------------------------------------
# Centres at j + 1/2; walking up, a centre exactly at the lower vertex y is in. The lowest
# row whose centre is at or above y (centre <= y) is floor(y - 1/2).
for y in [sp.Rational(k, 4) for k in range(-12, 13)]:
    row = sp.floor(y - sp.Rational(1, 2))
    holds(f"prestep-up row for y = {y}", row + sp.Rational(1, 2) <= y < row + sp.Rational(3, 2))
    step = row + sp.Rational(1, 2) - y
    holds(f"prestep-up step for y = {y} in (-1, 0]", -1 < step <= 0)

# --- ch02-block-area ------------------------------------------------------------------
# The edge value at the point (X, Y) of the block, w at the top-left centre (x0 + 1/2,
# y0 + 1/2): w + (X - x0 - 1/2) s_x + (Y - y0 - 1/2) s_y, X in [x0, x0 + n_x], Y likewise.
# A linear function on a rectangle is largest at a corner: offsets -1/2 or n - 1/2.
w, sx, sy = sp.symbols("w s_x s_y", real=True)
for nx in range(1, 5):
    for ny in range(1, 5):
        for sxv in (-3, 0, 2):
            for syv in (-5, 0, 7):
                corners = [w + ox * sxv + oy * syv
                           for ox in (-sp.Rational(1, 2), nx - sp.Rational(1, 2))
                           for oy in (-sp.Rational(1, 2), ny - sp.Rational(1, 2))]
                largest = (w + sp.Max(-sp.Rational(sxv, 2), (nx - sp.Rational(1, 2)) * sxv)
                           + sp.Max(-sp.Rational(syv, 2), (ny - sp.Rational(1, 2)) * syv))
                smallest = (w + sp.Min(-sp.Rational(sxv, 2), (nx - sp.Rational(1, 2)) * sxv)
                            + sp.Min(-sp.Rational(syv, 2), (ny - sp.Rational(1, 2)) * syv))
                same(f"block area max {nx}x{ny} ({sxv}, {syv})", sp.Max(*corners), largest)
                same(f"block area min {nx}x{ny} ({sxv}, {syv})", sp.Min(*corners), smallest)

# --- ch03-pixel-of-u ------------------------------------------------------------------
t, u = sp.symbols("t u")
p0, pt, q0, qt = sp.symbols("p0 p_t q0 q_t")
solved = sp.solve(sp.Eq((p0 + t * pt) / (q0 + t * qt), u), t)
holds("pixel-of-u: one solution", len(solved) == 1)
same("pixel-of-u", solved[0], (u * q0 - p0) / (pt - u * qt))

# --- ch03-quarter-point ---------------------------------------------------------------
u0, D, w0, w2, N = sp.symbols("u0 Delta w0 w2 n", positive=True)


def exact(tt):
    """u at pixel tt of a span of n steps from (u0, w0) to (u0 + D, w2): u/w and 1/w
    interpolated linearly on screen (@eq:linear-in-screen), then divided."""
    f = tt / N
    return (((1 - f) * u0 / w0 + f * (u0 + D) / w2) / ((1 - f) / w0 + f / w2))


k = 16 * D * w0 / (w0 + 3 * w2)
a = (4 * D - k) / (3 * N**2)
b = (k - D) / (3 * N)
quarter = u0 + b * t + a * t**2
same("quarter-point parabola at 0", quarter.subs(t, 0), exact(0))
same("quarter-point parabola at n/4", quarter.subs(t, N / 4), exact(N / 4))
same("quarter-point parabola at n", quarter.subs(t, N), exact(N))
same("k is 16 (u(n/4) - u0)", k, 16 * (exact(N / 4) - u0))
# Equal depths: the affine line.
same("quarter-point parabola, equal depths", quarter.subs(w2, w0), u0 + D * t / N)

# Its error against Pursey's, on the normalised span (t the fraction, r = w2 / w0):
# 4 (r - 1)^2 t (t - 1/4)(1 - t) / ((3 r + 1)(r - (r - 1) t)), of the same size as
# @eq:quadratic-error's at t = (2 r + 1) / (5 r + 3), smaller before, larger after.
r, f = sp.symbols("r f", positive=True)
s_exact = f / (r - (r - 1) * f)
quarter_n = sp.simplify((quarter.subs(t, f * N) - u0) / D).subs(w2, r * w0)
error_quarter = 4 * (r - 1)**2 * f * (f - sp.Rational(1, 4)) * (1 - f) / (
    (3 * r + 1) * (r - (r - 1) * f))
error_pursey = 2 * (r - 1)**2 * f * (f - sp.Rational(1, 2)) * (1 - f) / (
    (r + 1) * (r - (r - 1) * f))
same("quarter-point error", quarter_n - s_exact, error_quarter)
crossing = (2 * r + 1) / (5 * r + 3)
same("errors equal in size at the crossing",
     (error_quarter + error_pursey).subs(f, crossing), 0)
for rv in (sp.Rational(1, 5), 2, 4, 16):
    for fv in (sp.Rational(1, 10), sp.Rational(1, 3) * crossing.subs(r, rv)):
        holds(f"quarter-point smaller at f = {fv}, r = {rv}",
              abs(error_quarter.subs({r: rv, f: fv})) < abs(error_pursey.subs({r: rv, f: fv})))
    for fv in ((crossing.subs(r, rv) + 1) / 2, sp.Rational(3, 4), sp.Rational(99, 100)):
        holds(f"quarter-point larger at f = {fv}, r = {rv}",
              abs(error_quarter.subs({r: rv, f: fv})) > abs(error_pursey.subs({r: rv, f: fv})))

finish("ch01_ch02_ch03_variants.py")
