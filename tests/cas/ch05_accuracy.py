#!/usr/bin/env python3
"""Chapter 5, re-derived with SymPy (run by CTest, label book): what the texel error
(eq:texel-error) below one half says about the texel picked, the facing wall's share of
differing texels (eq:differing-share), that beating (eq:pareto, with times tied within
the noise, eq:time-tie) has no cycle, so every scene has a front, the depth
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


# @eq:pareto with @eq:time-tie: m' beats m when it is no slower beyond the noise delta
# ((1 + delta) t_m bounds t_m'), no worse on the worst error e and the wrong texels at
# ties N, and better on one (time: faster beyond the noise). With delta >= 0 the relation
# is irreflexive and has no cycle: along a cycle e and N could never fall, so every step
# would be faster beyond the noise, and t would fall all the way round. So every scene
# has a front (a finite set with an acyclic relation has an unbeaten member). It is not
# transitive once delta > 0: a chain of ties can span more than the noise, so the text
# may not say that a mapper off the front is beaten by one on it.
def beats(b, a, delta):
    no_slower = b[0] <= (1 + delta) * a[0]
    faster = (1 + delta) * b[0] < a[0]
    return (no_slower and b[1] <= a[1] and b[2] <= a[2]
            and (faster or b[1] < a[1] or b[2] < a[2]))


def tied(t, t_other, delta):
    return max(t, t_other) <= (1 + delta) * min(t, t_other)


for delta in (sp.Integer(0), sp.Rational(1, 20), sp.Rational(1, 4)):
    times = [sp.Rational(t, 20) for t in range(18, 27, 2)]
    grid = [(t, e, N) for t in times for e in range(2) for N in range(2)]
    # "No slower" is "faster or tied"; "faster" is "quicker and not tied" (the code's
    # form, pareto_front.cpp).
    for t, t_other in itertools.product(times, repeat=2):
        holds(f"no slower is faster or tied at {t}, {t_other}",
              (t <= (1 + delta) * t_other)
              == ((1 + delta) * t < t_other or tied(t, t_other, delta)))
        holds(f"faster is quicker and not tied at {t}, {t_other}",
              ((1 + delta) * t < t_other) == (t < t_other and not tied(t, t_other, delta)))
    for a in grid:
        holds(f"beats irreflexive at {a}, delta {delta}", not beats(a, a, delta))
    for a, b in itertools.product(grid, repeat=2):
        holds(f"no 2-cycle {a} {b}, delta {delta}", not (beats(a, b, delta) and beats(b, a, delta)))
    for a, b, c in itertools.product(grid, repeat=3):
        holds(f"no 3-cycle {a} {b} {c}, delta {delta}",
              not (beats(a, b, delta) and beats(b, c, delta) and beats(c, a, delta)))
        if delta == 0 and beats(a, b, delta) and beats(b, c, delta):
            holds(f"without noise, beating is transitive {a} {b} {c}", beats(a, c, delta))
    front = [m for m in grid if not any(beats(o, m, delta) for o in grid)]
    holds(f"the front is not empty, delta {delta}", len(front) > 0)
# With noise, beating is not transitive: y beats x (tied, fewer wrong texels at ties),
# z beats y (tied, smaller worst error), but z is slower than x beyond the noise.
delta = sp.Rational(1, 20)
x, y, z = (1, 1, 9), (sp.Rational(104, 100), 1, 0), (sp.Rational(108, 100), 0, 0)
holds("y beats x", beats(y, x, delta))
holds("z beats y", beats(z, y, delta))
holds("z does not beat x: beating is not transitive with noise", not beats(z, x, delta))

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
