#!/usr/bin/env python3
"""Chapter 6, re-derived with SymPy (run by CTest, label book): the float spacing near
10^6 px, the limit of the fixed-point range and how far past it an edge product
overflows, the edge-on error of the divide (eq:edge-on-error), the near-plane crossing
(eq:clip-t) with Exercise 2's error bound and its example in doubles, the drift of
stepping (eq:drift-bound) and of the 16.16 loop. Exits non-zero on any mismatch."""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402


# @sec:huge: the limit is 2^28 units of 1/256 px = 2^20 px; one unit past it is the value
# the error message names.
same("2^28 units are 2^20 px", sp.Integer(2)**28 / 256, sp.Integer(2)**20)
holds("one unit past the limit prints as 1048576.00390625",
      sp.Integer(2)**20 + sp.Rational(1, 256) == sp.Rational("1048576.00390625"))
# Within it every edge value is below 2^60 (chapter 2's eq:edge-range, L = 2^28 units), far
# from 2^63; a product of two differences reaches 2^63 only when each is 2^31.5 units,
# 2^23.5 px, that is with coordinates of about 2^22.5 px, some six million pixels.
L_units = sp.Integer(2)**28
holds("edge values below 2^60 at the limit", 8 * L_units**2 + 2**14 * L_units < sp.Integer(2)**60)
same("differences of 2^31.5 units multiply to 2^63", (sp.Integer(2)**sp.Rational(63, 2))**2,
     sp.Integer(2)**63)
same("2^31.5 units are 2^23.5 px", sp.Integer(2)**sp.Rational(63, 2) / 256,
     sp.Integer(2)**sp.Rational(47, 2))
holds("coordinates of 2^22.5 px are some six million pixels",
      5.5e6 < float(sp.Integer(2)**sp.Rational(45, 2)) < 6.5e6)

# @sec:far: a float has 24 significant bits; in [2^e, 2^(e+1)) its spacing is 2^(e-23).
# Near 2^20 the spacing is 1/8 px; 10^6 lies in [2^19, 2^20), spacing 1/16, so rounding
# to float moves a corner by at most 1/32 px.
holds("10^6 lies in [2^19, 2^20)", 2**19 <= 10**6 < 2**20)
same("spacing at 2^20", sp.Integer(2)**(20 - 23), sp.Rational(1, 8))
same("spacing at 10^6", sp.Integer(2)**(19 - 23), sp.Rational(1, 16))
same("largest move", sp.Integer(2)**(19 - 23) / 2, sp.Rational(1, 32))

# @eq:edge-on-error: u = p/q with p and q each off by a relative a, b of their own value.
# To first order the quotient's relative error is a - b.
p, q, a, b, eps = sp.symbols("p q a b epsilon", positive=True)
relative = (p * (1 + a) / (q * (1 + b)) - p / q) / (p / q)
first_order = sp.series(sp.series(relative, a, 0, 2).removeO(), b, 0, 2).removeO()
same("quotient error to first order", sp.expand(first_order).subs(a * b, 0), a - b)
# Each is rounded to eps of its largest value along the row: |a| <= eps max p / p and
# |b| <= eps max q / q. At the far pixel q = max q / R; where u = p/q is largest along the
# row, p = u q <= u_far max q, so max p / p <= R too: |a - b| <= 2 eps R.
R, qmax, ufar, umax = sp.symbols("R q_max u_far u_max", positive=True)
q_far = qmax / R
b_bound = eps * qmax / q_far
a_bound = eps * (ufar * qmax) / (ufar * q_far)  # max p <= u_far max q when u_far is largest
same("far pixel: eps max q / q", b_bound, eps * R)
same("far pixel: both together", a_bound + b_bound, 2 * eps * R)
# Anywhere else on the row p's relative error is at most eps R u_max / |u|, so in texels
# |u| (a + b) <= eps R (u_max + |u|) <= 2 eps R u_max.
u_here = sp.Symbol("u_here", positive=True)
a_anywhere = eps * (umax * qmax) / (u_here * q_far)
holds("in texels the error is at most 2 eps R u_max",
      sp.simplify(2 * eps * R * umax - u_here * (a_anywhere + b_bound)
                  - eps * R * (umax - u_here)) == 0)
# The test's float tolerance, 8 2^-24 R 4096, is that bound with a factor of 4 to spare
# for |u| up to 4096 texels.
same("float tolerance", 8 * sp.Integer(2)**-24 * R * 4096,
     4 * (2 * sp.Integer(2)**-24 * R) * 4096)

# @eq:clip-t: the depth a_z + t (b_z - a_z) on the edge equals n at t = (a_z - n)/(a_z - b_z)
az, bz, n_near, t = sp.symbols("a_z b_z n t", real=True)
solution = sp.solve(sp.Eq(az + t * (bz - az), n_near), t)
same("crossing parameter", solution[0], (az - n_near) / (az - bz))
same("the crossing's depth is n exactly (Exercise 2)",
     az + solution[0] * (bz - az), n_near)
# With a_z >= n > b_z: the denominator is at least n - b_z > 0, and 0 <= t < 1.
gap_in, gap_out = sp.symbols("g_in g_out", nonnegative=True)
positive_out = sp.Symbol("g_out_pos", positive=True)
inside = {az: n_near + gap_in, bz: n_near - positive_out}
denominator = (az - bz).subs(inside)
same("denominator is the two gaps", denominator, gap_in + positive_out)
t_value = solution[0].subs(inside)
holds("t >= 0", sp.simplify(t_value).is_nonnegative)
holds("t < 1", sp.simplify(1 - t_value).is_positive)
# u and v interpolated with the same t are those of the point: an affine function of view
# space is affine along the edge.
ax, ay, bx, by, c0, c1, c2, c3 = sp.symbols("a_x a_y b_x b_y c0 c1 c2 c3", real=True)
u_of = lambda x, y, z: c0 + c1 * x + c2 * y + c3 * z  # noqa: E731
point = [ax + t * (bx - ax), ay + t * (by - ay), az + t * (bz - az)]
same("texture coordinate at the crossing",
     u_of(*point), u_of(ax, ay, az) + t * (u_of(bx, by, bz) - u_of(ax, ay, az)))
# Exercise 2: z_hat = (a_z + e (1 + d3)(1 + d4))(1 + d5), e = (n - a_z)(1 + d2); to first
# order z_hat - n = (n - a_z)(d2 + d3 + d4) + n d5.
d2, d3, d4, d5 = sp.symbols("d2 d3 d4 d5", real=True)
e_rounded = (n_near - az) * (1 + d2)
z_hat = (az + e_rounded * (1 + d3) * (1 + d4)) * (1 + d5)
expanded = sp.expand(z_hat - n_near)
linear = sum(expanded.coeff(d, 1).subs({d2: 0, d3: 0, d4: 0, d5: 0}) * d
             for d in (d2, d3, d4, d5))
same("Exercise 2: first-order error of the crossing's depth",
     linear, (n_near - az) * (d2 + d3 + d4) + n_near * d5)
# Exercise 2, in doubles as clipping.cpp computes them (Python's floats are IEEE doubles,
# each operation rounded to nearest, no fused multiply-add): the first-order bound
# 3 eps |a_z - n| + eps n holds, and it is units in the last place of a_z, not of n. The
# solution's example: n = 0.1, a_z = 1234.5, b_z = -1 lands 6554 units of n below n.
import math  # noqa: E402
import random  # noqa: E402
from fractions import Fraction  # noqa: E402

eps_double = Fraction(1, 2**53)


def crossing_depth(a, b, near):
    """near_crossing's depth before it is set to near: a + t (b - a), t = (a - n)/(a - b)."""
    t_hat = (a - near) / (a - b)
    return a + t_hat * (b - a)


def first_order_bound(a, near):
    return 3 * eps_double * abs(Fraction(a) - Fraction(near)) + eps_double * Fraction(near)


z_example = crossing_depth(1234.5, -1.0, 0.1)
ulps_example = (Fraction(z_example) - Fraction(0.1)) / Fraction(math.ulp(0.1))
holds(f"exercise 2 example: 6554 units of n below n ({ulps_example})", ulps_example == -6554)
holds("exercise 2 example: behind the plane", z_example < 0.1)
holds("exercise 2 example: within the first-order bound",
      abs(Fraction(z_example) - Fraction(0.1)) <= first_order_bound(1234.5, 0.1))
sampler = random.Random(6)
for _ in range(20000):
    near = sampler.choice([1e-6, 1e-3, 0.1, 0.5])
    a_z = near + sampler.random() * 10**sampler.uniform(-3, 6)
    b_z = near - (sampler.random() + 1e-9) * 10**sampler.uniform(-3, 6)
    if not a_z >= near > b_z:
        continue
    miss = abs(Fraction(crossing_depth(a_z, b_z, near)) - Fraction(near))
    if miss > first_order_bound(a_z, near):
        holds(f"exercise 2 bound at n = {near}, a_z = {a_z}, b_z = {b_z}", False)
        break

# @sec:drift, the 16.16 loop: u0 and du rounded to 2^-16 (to_fixed_texel: u * 2^16 rounded
# to nearest) and added exactly, so pixel k is off by at most (1 + k) 2^-17; over the
# test's 4096 pixels the bound is 1/32 texel, and 1.0001 texels rounds by 0.45 of a unit,
# so the drift at the last pixel is more than half the bound.
same("16.16 bound over 4096 px", 4096 * sp.Integer(2)**-17, sp.Rational(1, 32))
U0, dU = round(Fraction(0.3) * 2**16), round(Fraction(1.0001) * 2**16)
holds("du rounds by 0.45 of a unit", abs(dU - Fraction(1.0001) * 2**16) > Fraction(44, 100))
fixed_drift = max(abs(Fraction(U0 + k * dU, 2**16) - (Fraction(0.3) + k * Fraction(1.0001)))
                  for k in range(4096))
holds(f"16.16 drift {float(fixed_drift)} within (1 + k) 2^-17 and above half of 1/32",
      Fraction(1, 64) < fixed_drift <= Fraction(1, 32))

# @eq:drift-bound: u_{j+1} = (u_j + du)(1 + d_j), |d_j| <= 2^-24. To first order
# u_k - (u_0 + k du) = sum_j d_j (u_0 + (j + 1) du): k terms, each at most 2^-24 max|u|.
k = 6
u0, du = sp.symbols("u0 du", real=True)
d = sp.symbols(f"d0:{k}", real=True)
u = u0
for step in range(k):
    u = (u + du) * (1 + d[step])
drift = sp.expand(u - (u0 + k * du))
first = sum(drift.coeff(d[step], 1).subs({x: 0 for x in d}) * d[step] for step in range(k))
same("drift to first order", first,
     sum(d[step] * (u0 + (step + 1) * du) for step in range(k)))
# Evaluating u0 + k du afresh rounds twice (the product and the sum) whatever k is.
e1, e2 = sp.symbols("e1 e2", real=True)
fresh = sp.expand((u0 + k * du * (1 + e1)) * (1 + e2) - (u0 + k * du))
fresh_first = fresh.coeff(e1, 1).subs(e2, 0) * e1 + fresh.coeff(e2, 1).subs(e1, 0) * e2
same("fresh evaluation to first order", fresh_first, k * du * e1 + (u0 + k * du) * e2)
# The test's span: u0 = 0.3, du = 1.0001, 4096 pixels: the bound n 2^-24 max|u| is about
# one texel, as the text says.
span_bound = 4096 * sp.Integer(2)**-24 * (sp.Rational("0.3") + 4096 * sp.Rational("1.0001"))
holds(f"drift bound over 4096 px is about 1 texel ({float(span_bound)})",
      sp.Rational(95, 100) < span_bound < sp.Rational(105, 100))

finish("ch06_hard_cases.py")
