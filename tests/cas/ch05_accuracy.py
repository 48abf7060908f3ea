#!/usr/bin/env python3
"""Chapter 5, re-derived with SymPy (run by CTest, label book): what the texel error
(eq:texel-error) below one half says about the texel picked, the facing wall's share of
differing texels (eq:differing-share), the Pareto front's dominance (eq:pareto), the depth
ratio of a piece (eq:piece-ratio) with its consequences in the text, the receding quad's
worst affine error, and Exercise 2's piece length. Exits non-zero on any mismatch."""
import itertools
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402


# @eq:texel-error: e = max(|u - u*|, |v - v*|) < 1/2 means "off by at most one texel":
# floor(u) and floor(u*) differ by at most one, and they differ only when u* is within e
# of a texel edge (an integer).
samples = [sp.Rational(n, 16) for n in range(-40, 41)]
for u_ref, u in itertools.product(samples, repeat=2):
    e = abs(u - u_ref)
    if e < sp.Rational(1, 2):
        step = abs(sp.floor(u) - sp.floor(u_ref))
        holds(f"texel error {e}: texels {sp.floor(u)} and {sp.floor(u_ref)}", step <= 1)
        if step == 1:
            edge = sp.floor(u_ref) if u < u_ref else sp.floor(u_ref) + 1
            holds(f"differing texel at u* = {u_ref} not near an edge", abs(u_ref - edge) <= e)

# @eq:differing-share on the facing wall: u = (304.5 - x)/2 at pixel centres x = i + 1/2
# is a whole number at every second pixel; there rule 1 (floor u) and chapter 4's rule
# (ceil u - 1) differ, and nowhere else, so d = 1/2 exactly.
columns = range(0, 304)
differ = 0
for column in columns:
    u = (sp.Rational(609, 2) - (column + sp.Rational(1, 2))) / 2
    rule1, rule2 = sp.floor(u), sp.ceiling(u) - 1
    holds(f"rules differ at column {column} exactly at a tie", (rule1 != rule2) == u.is_integer)
    differ += rule1 != rule2
same("facing wall: share of differing texels", sp.Rational(differ, len(columns)),
     sp.Rational(1, 2))


# @eq:pareto: "m' dominates m" is a strict partial order (irreflexive, transitive), so the
# front (the undominated mappers) is never empty and every mapper off it is dominated by
# one on it.
def dominates(a, b):
    return a[0] <= b[0] and a[1] <= b[1] and a != b


grid = [(sp.Rational(t, 4), sp.Rational(e, 3)) for t in range(4) for e in range(4)]
for a, b, c in itertools.product(grid, repeat=3):
    holds(f"dominance irreflexive at {a}", not dominates(a, a))
    if dominates(a, b) and dominates(b, c):
        holds(f"dominance transitive {a} {b} {c}", dominates(a, c))
front = [m for m in grid if not any(dominates(o, m) for o in grid)]
for m in grid:
    if m not in front:
        holds(f"{m} off the front is dominated by a front member",
              any(dominates(f, m) for f in front))

# @eq:piece-ratio: with q(k) = q0 + k dq > 0 on the piece, max/min = 1 + n |dq| / min,
# for either sign of dq.
q0, n, L = sp.symbols("q0 n L", positive=True)
dq = sp.Symbol("dq", positive=True)
for sign in (1, -1):
    a, b = q0, q0 + sign * n * dq
    high, low = (b, a) if sign > 0 else (a, b)
    same(f"piece ratio, dq of sign {sign}", high / low, 1 + n * dq / low)
# It falls in proportion to n: halving n halves r_piece - 1 ...
low = sp.Symbol("low", positive=True)
same("halving the piece halves r - 1", (1 + (n / 2) * dq / low) - 1, ((1 + n * dq / low) - 1) / 2)
# ... and the affine bound (sqrt r - 1)/(sqrt r + 1) is (r - 1)/4 to first order in r - 1.
r, h = sp.symbols("r h", positive=True)
bound = (sp.sqrt(r) - 1) / (sp.sqrt(r) + 1)
same("affine bound near r = 1", sp.series(bound.subs(r, 1 + h), h, 0, 2).removeO(), h / 4)
# The quadratic error of chapter 3 (eq:quadratic-error) carries (r - 1)^2.
t = sp.Symbol("t", positive=True)
quadratic = 2 * (r - 1)**2 * t * (t - sp.Rational(1, 2)) * (1 - t) / ((r + 1) * (r - (r - 1) * t))
same("quadratic error over (r - 1)^2 is finite at r = 1",
     sp.limit(quadratic / (r - 1)**2, r, 1), 2 * t * (t - sp.Rational(1, 2)) * (1 - t) / 2)

# The receding quad of @sec:error: r = 9, 100 texels: the bound is 50 texels.
same("receding quad bound", bound.subs(r, 9) * 100, 50)

# Exercise 2: the far piece has r_piece = 1 + n (r - 1)/L, and U (sqrt rp - 1)/(sqrt rp + 1)
# < 1/2 exactly when n < L/(r - 1) * 8U/(2U - 1)^2 (U > 1/2).
U = sp.Symbol("U", positive=True)
rp = sp.Symbol("rp", positive=True)
root = sp.solve(sp.Eq(U * (sp.sqrt(rp) - 1) / (sp.sqrt(rp) + 1), sp.Rational(1, 2)), rp)
same("limit on the piece ratio", root[0], ((2 * U + 1) / (2 * U - 1))**2)
n_limit = sp.solve(sp.Eq(1 + n * (r - 1) / L, ((2 * U + 1) / (2 * U - 1))**2), n)
same("limit on the piece length", n_limit[0], L / (r - 1) * 8 * U / (2 * U - 1)**2)
same("for large U about 2L/(U(r - 1))",
     sp.limit(n_limit[0] * U * (r - 1) / L, U, sp.oo), 2)

finish("ch05_accuracy.py")
