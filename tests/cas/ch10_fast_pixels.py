#!/usr/bin/env python3
"""Chapter 10, re-derived with SymPy (run by CTest, label book): a row's covered run
(eq:fast-run), its ends stepped by quotient, remainder and carry (eq:fast-step, with the
branchless step of RunEnd), the sign-OR coverage test (eq:fast-or) and Exercise 3's
AND and XOR, the int32 bound for tiny triangles (eq:tiny-bound) with the columns and rows
its lanes reach, the depth lanes' rounding (eq:fast-depth), and Exercise 2's numbers.
Exits non-zero on any mismatch."""
import itertools
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402


# @eq:fast-run: the columns k with w + k s_x >= 0 are k >= ceil(-w / s_x) for s_x > 0,
# k <= floor(w / -s_x) for s_x < 0, all or none for s_x = 0. Every small case.
def passes_by_case(w, s_x, k):
    if s_x > 0:
        return k >= sp.ceiling(sp.Rational(-w, s_x))
    if s_x < 0:
        return k <= sp.floor(sp.Rational(w, -s_x))
    return w >= 0


for w, s_x in itertools.product(range(-40, 41), range(-7, 8)):
    for k in range(-25, 26):
        if (w + k * s_x >= 0) != passes_by_case(w, s_x, k):
            holds(f"eq:fast-run at w = {w}, s_x = {s_x}, k = {k}", False)

# @eq:fast-step, symbolically. s_x = s > 0: k is the first passing column, e = w + k s;
# with s_y = Q s + R the next row's value at column k - Q is e + R, and one column left
# it is e + R - s. s_x = -s: k is one past the last passing column, e = w - (k - 1) s;
# the next row's value at column (k - 1) + Q is e + R, one column right e + R - s.
w, k, s, Q, R = sp.symbols("w k s Q R", integer=True)
s_y = Q * s + R
e_rise, e_fall = w + k * s, w - (k - 1) * s
same("s_x > 0: value at k - Q on the next row", (w + s_y) + (k - Q) * s, e_rise + R)
same("s_x > 0: value at k - Q - 1", (w + s_y) + (k - Q - 1) * s, e_rise + R - s)
same("s_x < 0: value at k - 1 + Q on the next row", (w + s_y) - (k - 1 + Q) * s, e_fall + R)
same("s_x < 0: value at k + Q", (w + s_y) - (k + Q) * s, e_fall + R - s)
# e and R are at most s - 1, so e + R - 2 s is at most -2: the next column never passes,
# and the carry is at most one column.
same("largest e + R - 2 s", (s - 1) + (s - 1) - 2 * s, -2)


def exact_end(w, s, rising):
    """The end run_end divides out: (k, e) for s_x = s (rising) or s_x = -s."""
    if rising:
        k = -((w) // s)  # ceil(-w / s)
        return k, w + k * s
    k = w // s + 1  # floor(w / s) + 1
    return k, w - (k - 1) * s


def branchless_step(k, e, s, q, r, sign):
    """RunEnd::step, in 64-bit two's complement (Python's >> is arithmetic)."""
    t = e + r - s
    keep = t >> 63
    return k + sign * (q + 1 + keep), t + (keep & s)


steps = 0
for s_, sy in itertools.product(range(1, 8), range(-25, 26)):
    q_, r_ = sy // s_, sy - (sy // s_) * s_  # floor division: 0 <= R < s
    for w_, rising in itertools.product(range(-60, 61), (True, False)):
        k_, e_ = exact_end(w_, s_, rising)
        c = 1 if e_ + r_ >= s_ else 0
        k_next = k_ - q_ - c if rising else k_ + q_ + c
        e_next = e_ + r_ - c * s_
        want_k, want_e = exact_end(w_ + sy, s_, rising)
        if (k_next, e_next) != (want_k, want_e) or not 0 <= e_next < s_:
            holds(f"eq:fast-step at s = {s_}, s_y = {sy}, w = {w_}, rising {rising}", False)
        if branchless_step(k_, e_, s_, q_, r_, -1 if rising else 1) != (k_next, e_next):
            holds(f"RunEnd::step at s = {s_}, s_y = {sy}, w = {w_}", False)
        steps += 1
holds("eq:fast-step: every small case tried", steps == 7 * 51 * 121 * 2)

# @eq:fast-or: in two's complement, all three values >= 0 exactly when the top bit of
# their OR is clear. The OR works bit by bit, so a width of 6 bits, tried exhaustively,
# is the argument for 64.
BITS = 6
top = 1 << (BITS - 1)
values = range(-top, top)
for a, b, c in itertools.product(values, repeat=3):
    o = (a | b | c) & ((1 << BITS) - 1)
    if (a >= 0 and b >= 0 and c >= 0) != (o & top == 0):
        holds(f"eq:fast-or at {a}, {b}, {c}", False)

# Exercise 3, on the six values' top bits (1 = negative). O_k = OR of triangle k's three;
# covered_k = top bit of O_k clear.
patterns = list(itertools.product((0, 1), repeat=6))


def covered(bits):
    return (not any(bits[:3]), not any(bits[3:]))


for bits in patterns:
    o1, o2 = int(any(bits[:3])), int(any(bits[3:]))
    one, two = covered(bits)
    holds(f"at least one is the AND's top bit clear, {bits}", (one or two) == ((o1 & o2) == 0))
    holds(f"exactly one is the XOR's top bit set, {bits}", (one != two) == ((o1 ^ o2) == 1))


def exactly_one(bits):
    one, two = covered(bits)
    return one != two


# An AND/OR expression's top bit is monotone in the six top bits: read as "clear", the
# answer can only go false -> true as a bit is cleared; read as "set", only true -> false.
# "Exactly one" goes both ways, so neither reading decides it.
up = down = None
for bits in patterns:
    for i in range(6):
        if bits[i] == 1:
            cleared = bits[:i] + (0,) + bits[i + 1:]
            before, after = exactly_one(bits), exactly_one(cleared)
            if not before and after:
                up = (bits, i)
            if before and not after:
                down = (bits, i)
holds("exactly one: clearing a top bit can turn it false -> true", up is not None)
holds("exactly one: clearing a top bit can turn it true -> false", down is not None)
# The solution's witnesses: triangle 1 has one negative value (bit 0); triangle 2 misses
# the pixel (one negative value of its own), or covers it.
holds("witness false -> true", not exactly_one((1, 0, 0, 1, 0, 0))
      and exactly_one((0, 0, 0, 1, 0, 0)))
holds("witness true -> false", exactly_one((1, 0, 0, 0, 0, 0))
      and not exactly_one((0, 0, 0, 0, 0, 0)))

# @eq:tiny-bound. Units of 1/256 px; pixel centres at 128 + 256 i; B = 2^13 (32 px).
B, unit = 2**13, 256
centres = max(
    sum(1 for i in range(-2, 40) if lo <= 128 + unit * i <= lo + B) for lo in range(unit))
holds("a vertex box 32 px wide holds at most 33 pixel centres", centres == 33)
# The lanes: a row of width W <= 4 is one four (columns 0..3); a wider row is read in
# fours from column 0 and stepped once past its last four, so the lanes reach column
# 4 ceil(W / 4) + 3, at most W + 6 (the test's corner), with equality for W = 1 mod 4.
reach = {W: 3 if W <= 4 else 4 * sp.ceiling(sp.Rational(W, 4)) + 3 for W in range(1, 34)}
holds("the lanes reach column 39 at most", max(reach.values()) == 39)
holds("at most seven columns past the box's last (W - 1)",
      all(reach[W] <= (W - 1) + 7 for W in reach))
holds("the test's corner x_end + 6 is the farthest column",
      all(reach[W] <= W + 6 for W in reach) and reach[33] == 33 + 6)
rows = 33  # the rows are stepped once past the last of at most 33 rows: offset 33
holds("every point evaluated within 40 px = 40 * 256 < 2^14 units of the origin",
      max(39, rows) < 40 and 40 * unit < 2**14)
# The origin is in the vertex box, so each vertex and each difference is within B; a
# point p evaluated is within 2^14 + 2^13 of an edge's start a in each coordinate.
bound = 2 * B * (2**14 + B) + 1
same("the bound", bound, 3 * 2**27 + 1)
holds("the bound is under 2^29", bound < 2**29)
holds("and far under 2^31", 4 * bound < 2**31)
# The setup in int32: twice the area and the value at the origin are products of two
# numbers within B; the steps 256 d and 4 * 256 d stay small.
holds("setup products within int32", 2 * B * B < 2**31 and 4 * unit * B < 2**31)


# @eq:fast-depth: IEEE single precision, 24-bit significand, round to nearest even.
def fl32(v):
    """v rounded to the nearest float (ties to even), exactly, for normal v."""
    v = sp.Rational(v)
    if v == 0:
        return v
    exponent = sp.floor(sp.log(abs(v), 2))
    while 2**exponent > abs(v):
        exponent -= 1
    while 2**(exponent + 1) <= abs(v):
        exponent += 1
    ulp = sp.Rational(2) ** (exponent - 23)
    m = v / ulp
    n = sp.floor(m)
    if m - n > sp.Rational(1, 2) or (m - n == sp.Rational(1, 2) and n % 2 == 1):
        n += 1
    return n * ulp


holds("every integer below 2^24 is a float (x converts exactly)",
      all(fl32(x) == x for x in (1, 4095, 2**24 - 3, 2**24 - 1, 2**24)))
holds("2^24 + 1 is not: the limit is tight", fl32(2**24 + 1) != 2**24 + 1)
holds("x + 4 is exact below 2^24", all(fl32(x + 4) == x + 4 for x in (2**24 - 5, 2**23 + 1)))
# Two roundings, product then sum, as at() and the lanes do, are not one rounding of
# x dzdx + row (a fused multiply-add): a plane, a column and a row part where they differ.
dzdx = fl32(sp.Rational(1, 3))
row_part = fl32(sp.Rational(1, 7))
differs = [x for x in range(1, 200)
           if fl32(row_part + fl32(x * dzdx)) != fl32(row_part + x * dzdx)]
holds("a fused multiply-add would give other bits", len(differs) > 0)

# Exercise 2's numbers, in the doubles Python computes with: for |s_x| = 455 858 542 515
# and k* = 242 215 + 1/|s_x| the estimate rounds below 242 215, two columns short of
# ceil(k*); |w| lies between 2^52 and 2^60.
s_big = 455858542515
w_big = -(242215 * s_big + 1)
estimate = -(float(w_big) * (1.0 / float(s_big)))
holds("|w| between 2^52 and 2^60", 2**52 <= abs(w_big) < 2**60)
holds("the estimate is 242214.99999999997", repr(estimate) == "242214.99999999997")
holds("two columns short", sp.ceiling(sp.Rational(-w_big, s_big)) - int(estimate) == 2)
L = 2**24
holds("8 L^2 + 2^14 L < 2^52 for L = 2^24", 8 * L**2 + 2**14 * L < 2**52)
holds("3 2^-53 2^20 lies between 2^-32 and 2^-31",
      sp.Rational(1, 2**32) < 3 * sp.Rational(2**20, 2**53) < sp.Rational(1, 2**31))

finish("ch10_fast_pixels.py")
