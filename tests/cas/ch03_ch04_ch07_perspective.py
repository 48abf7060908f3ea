#!/usr/bin/env python3
"""Chapters 3, 4 and 7, re-derived with SymPy (run by CTest, label book): the exact
fraction and the affine error along a span (eq:exact-fraction, eq:affine-error), where
it peaks and how large it is (eq:affine-worst-t, eq:affine-bound), the error when the
span's ends are off (eq:affine-plane-error), the exact midpoint
(eq:midpoint), Pursey's and Thellier's coefficients (eq:pursey, eq:thellier), forward
differences (eq:forward-differences), chapter 4's numerator (eq:numerator,
eq:numerator-constant, eq:step-difference), and chapter 7's quadratic bound
(eq:scene-quadratic-bound, from its two bounds and the symmetry in r and 1/r), the texel
extent of a piece behind eq:scene-worst-piece, exercises 3, 4 and 6 and the slope bound
of the sRGB encode behind eq:scene-referee-lit. Exits non-zero on any mismatch."""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import failures, same, finish  # noqa: E402

t, r, n, k = sp.symbols("t r n k", positive=True)
u0, u2, w0, w2, T = sp.symbols("u0 u2 w0 w2 T")


# eq:linear-in-screen: a point (x, y, z) of the plane n . (x, y, z) = d seen at
# X = ox + f x / z, Y = oy - f y / z; u = ax x + ay y + az z on the plane.
xv, yv, zv, f_, ox, oy, ax, ay, az, nx, ny, nz, dd = sp.symbols(
    "x y z f o_x o_y a_x a_y a_z n_x n_y n_z d", nonzero=True)
Xs, Ys = ox + f_ * xv / zv, oy - f_ * yv / zv
same("u/w is affine in X, Y", (ax * xv + ay * yv + az * zv) / zv,
     ax * (Xs - ox) / f_ + ay * (oy - Ys) / f_ + az)
on_plane = {zv: (dd - nx * xv - ny * yv) / nz}
same("1/w is affine in X, Y", (1 / zv).subs(on_plane),
     ((nx * (Xs - ox) / f_ + ny * (oy - Ys) / f_ + nz) / dd).subs(on_plane))
# A span with u0 at depth w0 and u2 at w2 = r w0: u/w and 1/w linear in t.
u_exact = ((1 - t) * u0 / w0 + t * u2 / w2) / ((1 - t) / w0 + t / w2)
s = sp.simplify(((u_exact - u0) / (u2 - u0)).subs(w2, r * w0))
same("exact fraction", s, t / (r - (r - 1) * t))
e = t - t / (r - (r - 1) * t)
same("affine error", e, (r - 1) * t * (1 - t) / (r - (r - 1) * t))
t_star = (r - sp.sqrt(r)) / (r - 1)
same("affine error peaks at t*", sp.diff(e, t).subs(t, t_star), 0)
same("t* second form", t_star, sp.sqrt(r) / (sp.sqrt(r) + 1))
same("affine bound", e.subs(t, t_star), (sp.sqrt(r) - 1) / (sp.sqrt(r) + 1))
# The affine mapper with its ends off by d0 and d1 (taken from the triangle's plane):
# a straight line from u0 + d0 to u2 + d1 against the exact u (eq:affine-plane-error).
d0, d1 = sp.symbols("d0 d1")
line = (u0 + d0) + t * ((u2 + d1) - (u0 + d0))
same("affine error with plane ends",
     (line - u_exact).subs(w2, r * w0), (1 - t) * d0 + t * d1 + (u2 - u0) * e)
same("midpoint", u_exact.subs(t, sp.Rational(1, 2)), u0 + w0 * (u2 - u0) / (w0 + w2))
# Pursey's parabola over n pixel steps, and Thellier's form of its coefficients.
u1 = u0 + w0 * (u2 - u0) / (w0 + w2)
a = (2 * u0 - 4 * u1 + 2 * u2) / n**2
b = (-3 * u0 + 4 * u1 - u2) / n
parabola = a * T**2 + b * T + u0
for name, at, value in [("start", 0, u0), ("middle", n / 2, u1), ("end", n, u2)]:
    same(f"parabola through the {name}", parabola.subs(T, at), value)
delta, kk = u2 - u0, 4 * (u2 - u0) * w0 / (w0 + w2)
same("Thellier a", a, (2 * delta - kk) / n**2)
same("Thellier b", b, (kk - delta) / n)
same("first difference", parabola.subs(T, T + 1) - parabola, 2 * a * T + a + b)
same("second difference",
     parabola.subs(T, T + 2) - 2 * parabola.subs(T, T + 1) + parabola, 2 * a)
# Chapter 4: u = (p + t px) / (q + t qx) along a row (p = u/w, q = 1/w).
p, px, q, qx = sp.symbols("p p_x q q_x")
cc = (p + t * px) / (q + t * qx)
numerator = px * q - p * qx
same("numerator", sp.diff(cc, t), numerator / (q + t * qx)**2)
# c = u - 1/2 changes as u does, and interpolating c/w = p - q/2 gives the same numerator.
same("c steps as u", sp.diff(cc - sp.Rational(1, 2), t), sp.diff(cc, t))
same("numerator of c/w", (px - qx / 2) * q - (p - q / 2) * qx, numerator)
# From row to row (s pixels down) the numerator is n + s (px qy - py qx), not constant.
py_, qy, s_ = sp.symbols("p_y q_y s")
same("numerator down the rows", px * (q + s_ * qy) - (p + s_ * py_) * qx,
     numerator + s_ * (px * qy - py_ * qx))
same("numerator constant",
     sp.Matrix([[px, p + t * px], [qx, q + t * qx]]).det(), numerator)
same("step difference", cc.subs(t, t + 1) - cc,
     numerator / ((q + t * qx) * (q + (t + 1) * qx)))
# Exercise 4.4: the wall of the test, corners (10, 10.5), (74, 34.5), (10, 74.5) with
# w = 1, 4, 1 and v = 0, 0, 64: the planes of q = 1/w and p = v/w, the point P where both
# vanish, and the change of the x numerator per row.
X, Y = sp.symbols("X Y")
corners = [(10, sp.Rational(21, 2)), (74, sp.Rational(69, 2)), (10, sp.Rational(149, 2))]
w_wall, v_wall = [1, 4, 1], [0, 0, 64]


def plane_through(values):
    a0, a1, a2 = sp.symbols("a0 a1 a2")
    solution = sp.solve([a0 + a1 * cx_ + a2 * cy_ - value
                         for (cx_, cy_), value in zip(corners, values)], [a0, a1, a2])
    return solution[a0] + solution[a1] * X + solution[a2] * Y


q_wall = plane_through([sp.Integer(1) / w for w in w_wall])
p_wall = plane_through([sp.Integer(v) / w for v, w in zip(v_wall, w_wall)])
same("exercise 4.4: q", q_wall, sp.Rational(143, 128) - sp.Rational(3, 256) * X)
same("exercise 4.4: p", p_wall, Y - sp.Rational(27, 4) - sp.Rational(3, 8) * X)
P = sp.solve([q_wall, p_wall], [X, Y])
same("exercise 4.4: P x", P[X], sp.Rational(286, 3))
same("exercise 4.4: P y", P[Y], sp.Rational(85, 2))
same("exercise 4.4: numerator change per row",
     sp.diff(p_wall, X) * sp.diff(q_wall, Y) - sp.diff(p_wall, Y) * sp.diff(q_wall, X),
     sp.Rational(3, 256))
# Seed 004's equation 14 (erratum): in its letters A = p, B = px, C = q, D = qx, the step is
# (A + B)/(C + D) - A/C = (BC - AD)/(C (C + D)); subtracting A/B is not.
A, B, C, Dd = p, px, q, qx
same("seed 004 eq. 14, corrected", (A + B) / (C + Dd) - A / C,
     (B * C - A * Dd) / (C * (C + Dd)))
if sp.simplify((A + B) / (C + Dd) - A / B - (B * C - A * Dd) / (C * (C + Dd))) == 0:
    failures.append("seed 004's A/B would be right: the erratum is wrong")
# Chapter 7: |t (t - 1/2)(1 - t)| peaks at t = 1/2 -+ sqrt(3)/6 with sqrt(3)/36, and
# t (1 - t) / (s - (s - 1) t) <= 1 / (4 sqrt s) for s >= 1 (AM-GM on s (1 - t) + t).
cubic = t * (t - sp.Rational(1, 2)) * (1 - t)
for root in sp.solve(sp.diff(cubic, t), t):
    same("cubic peak", sp.Abs(cubic.subs(t, root)), sp.sqrt(3) / 36)
    same("cubic peak position", sp.Abs(root - sp.Rational(1, 2)), sp.sqrt(3) / 6)
sv = sp.symbols("s", positive=True)
gap = (sv * (1 - t) + t) - 2 * sp.sqrt(sv * t * (1 - t))
same("AM-GM gap is a square", gap,
     (sp.sqrt(sv * (1 - t)) - sp.sqrt(t))**2)
# eq:scene-quadratic-bound assembled from eq:quadratic-error: the error is the same for r
# and 1/r read from the other end (t -> 1 - t, up to its sign), so with s = max(r, 1/r)
# and k = s - 1 it is 2 k^2 |cubic| / ((s + 1)(s - k t)); the two bounds above give
# k^2/(s + 1) times sqrt(3)/18 and times 1/(4 sqrt s).
quadratic_error = 2 * (r - 1)**2 * cubic / ((r + 1) * (r - (r - 1) * t))
same("quadratic error: r and 1/r read backwards",
     quadratic_error.subs({r: 1 / r, t: 1 - t}, simultaneous=True), -quadratic_error)
kv = sv - 1
with_s = 2 * kv**2 * cubic / ((sv + 1) * (sv - kv * t))
same("quadratic error in s", with_s, quadratic_error.subs(r, sv))
same("first bound", 2 * kv**2 / (sv + 1) * sp.sqrt(3) / 36,
     kv**2 / (sv + 1) * sp.sqrt(3) / 18)
same("second bound", 2 * kv**2 / (sv + 1) * sp.Rational(1, 2) / (4 * sp.sqrt(sv)),
     kv**2 / (sv + 1) / (4 * sp.sqrt(sv)))
# Both bounds grow with s > 1 (each derivative is a product of positive factors), so the
# bound is largest where a piece's ratio is: the worst piece lies at an end of the span
# (eq:scene-worst-piece).
same("first bound grows", sp.diff(kv**2 / (sv + 1), sv),
     (sv - 1) * (sv + 3) / (sv + 1)**2)
same("second bound grows", sp.diff(kv**2 / ((sv + 1) * sp.sqrt(sv)), sv),
     (sv - 1) * (sv**2 + 6 * sv + 1) / (2 * sv**sp.Rational(3, 2) * (sv + 1)**2))
# eq:scene-worst-piece: u = p/q with p = p_0 + k p_x and q = q_0 + k q_x changes over a
# piece of N pixels by N (p_x q - p q_x) / (q(k) q(k + N)), chapter 4's numerator
# (eq:numerator), the same at every k, over the product of the end values of q.
kk_, NN = sp.symbols("k N", positive=True)
u_of_k = (p + kk_ * px) / (q + kk_ * qx)
same("texel extent of a piece", u_of_k.subs(kk_, kk_ + NN) - u_of_k,
     NN * (px * q - p * qx) / ((q + kk_ * qx) * (q + (kk_ + NN) * qx)))
# Chapter 7, exercise 3: with u(k) = (a + b k)/(c + d k), the change over k0..k1 is
# (k1 - k0)(b c - a d)/(q0 q1); exercise 4: t (1 - t)/(s - (s - 1) t) peaks at
# t* = sqrt s/(sqrt s + 1) with 1/(sqrt s + 1)^2, and (s - 1)/(sqrt s + 1)^2 is chapter
# 3's (sqrt s - 1)/(sqrt s + 1); 1/(4 sqrt s) overestimates it by (sqrt s + 1)^2/(4 sqrt s).
a3, b3, c3, d3, k0, k1 = sp.symbols("a b c d k0 k1")
u3 = lambda kv_: (a3 + b3 * kv_) / (c3 + d3 * kv_)  # noqa: E731
same("exercise 3: change over a piece", u3(k1) - u3(k0),
     (k1 - k0) * (b3 * c3 - a3 * d3) / ((c3 + d3 * k0) * (c3 + d3 * k1)))
g4 = t * (1 - t) / (sv - (sv - 1) * t)
t4 = sp.sqrt(sv) / (sp.sqrt(sv) + 1)
same("exercise 4: stationary point", sp.numer(sp.together(sp.diff(g4, t))).subs(t, t4), 0)
same("exercise 4: maximum", g4.subs(t, t4), 1 / (sp.sqrt(sv) + 1)**2)
same("exercise 3: affine maximum", (sv - 1) / (sp.sqrt(sv) + 1)**2,
     (sp.sqrt(sv) - 1) / (sp.sqrt(sv) + 1))
same("exercise 4: overestimate", (1 / (4 * sp.sqrt(sv))) / g4.subs(t, t4),
     (sp.sqrt(sv) + 1)**2 / (4 * sp.sqrt(sv)))
# Exercise 6: with m = b + t (c - b), (m - a) x (b - a) + (c - a) x (m - a) = (c - a) x (b - a).
av, bv, cv = (sp.Matrix(sp.symbols(f"{n}0:3")) for n in ("a", "b", "c"))
mv = bv + t * (cv - bv)
same("exercise 6: the split keeps the weighted sum at a",
     ((mv - av).cross(bv - av) + (cv - av).cross(mv - av) - (cv - av).cross(bv - av)).norm(), 0)
# eq:scene-referee-lit: the sRGB encode E (12.92 x up to 0.0031308, then
# 1.055 x^(1/2.4) - 0.055) has a slope that never grows (the power piece starts below
# 12.92), x E'(x) <= 0.45 x^(5/12) on both pieces, and 255 * 0.45 <= 115.
xe = sp.Symbol("x", positive=True)
power_piece = sp.Rational(1055, 1000) * xe**(1 / sp.Rational(24, 10)) - sp.Rational(55, 1000)
knee = sp.Rational(31308, 10**7)
if not sp.diff(power_piece, xe).subs(xe, knee) < sp.Rational(1292, 100):
    failures.append("the encode's slope grows at the knee")
same("x E'(x) on the power piece", xe * sp.diff(power_piece, xe),
     sp.Rational(1055, 2400) * xe**sp.Rational(5, 12))
if not sp.Rational(1055, 2400) <= sp.Rational(45, 100):
    failures.append("0.45 does not bound the power piece")
# On the straight piece x E'(x) = 12.92 x, at most 0.45 x^(5/12) while x^(7/12) <= 0.45/12.92.
if not knee**7 <= (sp.Rational(45, 100) / sp.Rational(1292, 100))**12:
    failures.append("0.45 x^(5/12) does not bound the straight piece up to the knee")
if not 255 * sp.Rational(45, 100) <= 115:
    failures.append("255 * 0.45 > 115")
finish("ch03_ch04_ch07_perspective.py")
