#!/usr/bin/env python3
"""Chapters 1 and 2, re-derived with SymPy (run by CTest, label book): the split-edge
gradient (eq. 1.3-1.6), its denominator (eq:split-denominator) with the book's one sign
for twice the signed area, 2A, the closed form (eq:closed-form) as the solution of the
plane through three vertices, Exercise 1.3's reading of its numerators, and chapter 2's
edge sum (eq:edge-sum), barycentric interpolation (eq:edge-barycentric), edge steps
(eq:edge-steps) and edge gradient (eq:edge-gradient). Exits non-zero on any mismatch."""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import failures, same, finish  # noqa: E402

x1, y1, x2, y2, x3, y3, c1, c2, c3, px, py = sp.symbols("x1 y1 x2 y2 x3 y3 c1 c2 c3 px py")


# The plane through the three vertices (eq:plane), solved directly.
cx, cy = sp.symbols("cx cy")
plane = sp.solve([c1 + cx * (x2 - x1) + cy * (y2 - y1) - c2,
                  c1 + cx * (x3 - x1) + cy * (y3 - y1) - c3], [cx, cy])
# Twice the signed area, one sign for the book: 2A = (p2 - p1) x (p3 - p1), positive when
# the vertices run clockwise on screen (y down); chapter 2's eq:edge-area is the same.
A2 = (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1)
Nx = (c2 - c1) * (y3 - y1) - (c3 - c1) * (y2 - y1)
Ny = (c3 - c1) * (x2 - x1) - (c2 - c1) * (x3 - x1)
same("closed form c_x", plane[cx], Nx / A2)
same("closed form c_y", plane[cy], Ny / A2)
# Exercise 1.3: the numerators are 2A written for the points (c, y) and (x, c).
same("N_x is 2A of the points (c_i, y_i)", Nx, A2.subs({x1: c1, x2: c2, x3: c3}, simultaneous=True))
same("N_y is 2A of the points (x_i, c_i)", Ny, A2.subs({y1: c1, y2: c2, y3: c3}, simultaneous=True))
# ... and 2A is a cyclic sum of cross products, so exchanging two vertices negates it.
cross = lambda ax, ay, bx, by: ax * by - ay * bx
same("2A as a cyclic sum", A2, cross(x1, y1, x2, y2) + cross(x2, y2, x3, y3) + cross(x3, y3, x1, y1))
same("exchanging vertices 1 and 2 negates 2A",
     A2.subs({x1: x2, y1: y2, x2: x1, y2: y1}, simultaneous=True), -A2)
# Split edge: point 4 on edge 1-3 at y2 (eq:split-point), then eq:split-dcdx.
t = (y2 - y1) / (y3 - y1)
x4, c4 = x1 + t * (x3 - x1), c1 + t * (c3 - c1)
same("split denominator", x4 - x2, -A2 / (y3 - y1))
same("split c_x", (c4 - c2) / (x4 - x2), plane[cx])
same("split c_y", (c3 - c1) / (y3 - y1) - plane[cx] * (x3 - x1) / (y3 - y1), plane[cy])

# Exercise 1.4: c_x off by delta. Stepped down the edge by the gradient form
# (eq:edge-slope-gradient) and along the row by eq:prestep, the value is a plane; with the
# direct edge slope (eq:edge-slope-direct) it is off by delta times the distance from the
# edge.
xa, ya, ca, m, dl, X, Y = sp.symbols("x_a y_a c_a m delta X Y")
exact_plane = ca + cx * (X - xa) + cy * (Y - ya)
x_edge = xa + m * (Y - ya)
by_gradient = ca + (Y - ya) * ((cx + dl) * m + cy) + (X - x_edge) * (cx + dl)
by_direct = ca + (Y - ya) * (cx * m + cy) + (X - x_edge) * (cx + dl)
same("exercise 1.4: gradient slope error", by_gradient - exact_plane, dl * (X - xa))
same("exercise 1.4: direct slope error", by_direct - exact_plane, dl * (X - xa - m * (Y - ya)))

# Chapter 2: vertices v0, v1, v2 = (x1, y1), (x2, y2), (x3, y3); E_i is the edge opposite
# v_i, from v_{i+1} to v_{i+2}.
v = [(x1, y1), (x2, y2), (x3, y3)]
c = [c1, c2, c3]


def edge(a, b, p):
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


p = (px, py)
E = [edge(v[(i + 1) % 3], v[(i + 2) % 3], p) for i in range(3)]
area2 = edge(v[0], v[1], v[2])
same("chapter 2's 2A (eq:edge-area) is chapter 1's", area2, A2)
same("edge sum", sum(E), area2)
interpolated = sum(E[i] * c[i] for i in range(3)) / area2
same("barycentric interpolation is the plane",
     interpolated, c1 + plane[cx] * (px - x1) + plane[cy] * (py - y1))
for i in range(3):
    a, b = v[(i + 1) % 3], v[(i + 2) % 3]
    same(f"edge step x, E{i}", E[i].subs(px, px + 1) - E[i], -(b[1] - a[1]))
    same(f"edge step y, E{i}", E[i].subs(py, py + 1) - E[i], b[0] - a[0])
grad_x = -sum(c[i] * (v[(i + 2) % 3][1] - v[(i + 1) % 3][1]) for i in range(3)) / area2
grad_y = sum(c[i] * (v[(i + 2) % 3][0] - v[(i + 1) % 3][0]) for i in range(3)) / area2
same("edge gradient x", grad_x, plane[cx])
same("edge gradient y", grad_y, plane[cy])
# Not only the quotients: numerator for numerator, the same cross products as chapter 1's.
same("edge gradient numerator x",
     -sum(c[i] * (v[(i + 2) % 3][1] - v[(i + 1) % 3][1]) for i in range(3)), Nx)
same("edge gradient numerator y",
     sum(c[i] * (v[(i + 2) % 3][0] - v[(i + 1) % 3][0]) for i in range(3)), Ny)
# Seed 002's form (erratum): its dp/dx is the x-difference sum times -1/A^2.
seed_dx = sum(c[i] * (v[(i + 2) % 3][0] - v[(i + 1) % 3][0]) for i in range(3)) \
    * (-1 / area2) / area2
if sp.simplify(seed_dx - plane[cx]) == 0:
    failures.append("seed 002's dp/dx would be right: the erratum is wrong")
finish("ch01_ch02_gradients.py")
