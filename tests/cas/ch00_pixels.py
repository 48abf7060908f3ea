#!/usr/bin/env python3
"""Chapter 0, re-derived with SymPy (run by CTest, label book): the pixel square
(eq:pixel-square) and its storage index, the pixel centre (eq:pixel-centre) and which
integer edges pass through one (the text and Exercise 2), and the snap (eq:snap): nearest
with halves up, shift-invariant, and the one double input where floor(256 x + 1/2) computed
in floating point is wrong. Exits non-zero on any mismatch."""
import itertools
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402


# @eq:pixel-square: P_ij = [i, i+1) x [j, j+1). The squares tile the plane: a point lies in
# exactly one of them, the one with i = floor(x), j = floor(y); half-open intervals put a
# point on a shared side into one square only.
points = [sp.Rational(n, 7) for n in range(-15, 16)] + [sp.Integer(k) for k in range(-2, 3)]
for x, y in itertools.product(points, repeat=2):
    owners = [(i, j) for i in range(-4, 4) for j in range(-4, 4)
              if i <= x < i + 1 and j <= y < j + 1]
    holds(f"pixel square: ({x}, {y}) lies in {owners}, not one square",
          owners == [(sp.floor(x), sp.floor(y))])
# Rows top to bottom: pixel (i, j) of a W x H frame is element j W + i, one to one.
W, H = 5, 3
indices = [j * W + i for j in range(H) for i in range(W)]
holds("pixel (i, j) -> j W + i is one to one onto 0 .. WH-1", sorted(indices) == list(range(W * H)))

# @eq:pixel-centre: s_ij is the centre of P_ij, the mean of its corners.
i, j = sp.symbols("i j", integer=True)
same("centre x", (i + (i + 1)) / 2, i + sp.Rational(1, 2))
same("centre y", (j + (j + 1)) / 2, j + sp.Rational(1, 2))


def passes_through_centre(p, q):
    """Whether the closed segment p-q holds a point with both coordinates in Z + 1/2,
    solved exactly: the points of the segment at parameter s = k / (2 m), m the gcd."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    steps = 2 * max(sp.gcd(dx, dy), 1)
    for k in range(steps + 1):
        s = sp.Rational(k, steps)
        x, y = p[0] + s * dx, p[1] + s * dy
        if (x - sp.Rational(1, 2)).is_integer and (y - sp.Rational(1, 2)).is_integer:
            return True
    return False


def two_adic(n):
    return sp.multiplicity(2, abs(n)) if n != 0 else None


# The text: an edge between integer points meets a centre exactly when dx and dy are both
# non-zero and the largest powers of two dividing them are equal; Exercise 2: when the reduced direction (dx, dy)/g
# has both components odd. Both, against the exact search above, for every edge from the
# origin to a point of [-6, 6]^2 (every integer edge is one of these, shifted).
for dx, dy in itertools.product(range(-6, 7), repeat=2):
    if dx == 0 and dy == 0:
        continue
    meets = passes_through_centre((0, 0), (dx, dy))
    shared = dx != 0 and dy != 0 and two_adic(dx) == two_adic(dy)
    g = sp.gcd(dx, dy)
    odd = (dx // g) % 2 != 0 and (dy // g) % 2 != 0
    holds(f"edge (0,0)-({dx},{dy}): centre {meets}, shared power of two {shared}",
          meets == shared)
    holds(f"edge (0,0)-({dx},{dy}): centre {meets}, reduced direction odd {odd}",
          meets == odd)
holds("the edge (0,0)-(2,2) passes through (1/2, 1/2)", passes_through_centre((0, 0), (2, 2)))
# Exercise 2, "how often": of all integer edge vectors in a large square, a third have a
# reduced direction with both components odd (odd-odd, odd-even and even-odd are equally
# common among reduced directions; even-even is not reduced).
import math  # noqa: E402
vectors = odd_odd = 0
for dx in range(-200, 201):
    for dy in range(-200, 201):
        if dx == 0 and dy == 0:
            continue
        g = math.gcd(dx, dy)
        vectors += 1
        odd_odd += (dx // g) % 2 != 0 and (dy // g) % 2 != 0
holds(f"a third of the edge vectors meet centres: {odd_odd}/{vectors}",
      abs(odd_odd / vectors - 1 / 3) < 0.005)

# @eq:snap: X = floor(256 x + 1/2) is the nearest integer to 256 x, halves up ...
x = sp.Symbol("x", real=True)
k = sp.Symbol("k", integer=True)
for n in range(-600, 601):
    value = sp.Rational(n, 512)  # every half unit, ties included
    X = sp.floor(256 * value + sp.Rational(1, 2))
    holds(f"snap({value}) is nearest", abs(X - 256 * value) <= sp.Rational(1, 2))
    if (256 * value - sp.Rational(1, 2)).is_integer:
        holds(f"snap({value}) sends a half up", X == 256 * value + sp.Rational(1, 2))
# ... and shifting x by k/256 px shifts X by exactly k.
same("snap is shift-invariant",
     sp.floor(256 * (x + k / 256) + sp.Rational(1, 2)),
     sp.floor(256 * x + sp.Rational(1, 2)) + k)
# The one place where the formula evaluated in double is not the formula (chapter 2,
# @sec:edge-range): the largest double below 1/2, divided by 256. Exactly it snaps to 0;
# in double, 256 x + 0.5 rounds up to 1.0.
tricky = 0.49999999999999994 / 256
holds("the tricky value snaps to 0 exactly",
      sp.floor(256 * sp.Rational(tricky) + sp.Rational(1, 2)) == 0)
holds("in double floor(256 x + 0.5) gives 1 for it", int(tricky * 256 + 0.5) == 1)

finish("ch00_pixels.py")
