#!/usr/bin/env python3
"""Chapter 7's clipping against the view volume, re-derived with SymPy (run by CTest,
label book): the guard-band planes (eq:scene-guard-band), the crossing on any plane and
an example of its rounding in doubles, the band's size against the fixed-point range,
and the far-plane row (eq:scene-far-row).
Exits non-zero on any mismatch."""
import pathlib
import sys

import sympy as sp

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "support"))
from derivation import holds, same, finish  # noqa: E402

x, y, cx, cy, f, B = sp.symbols("x y c_x c_y f B", real=True)
z = sp.Symbol("z", positive=True)

# @eq:scene-guard-band: for z > 0 each plane value is z times the screen distance to the
# band's line, so its sign is that of the screen test.
xs, ys = cx + f * x / z, cy - f * y / z
same("x_s <= B plane", (B - cx) * z - f * x, z * (B - xs))
same("x_s >= -B plane", (B + cx) * z + f * x, z * (xs + B))
same("y_s <= B plane", (B - cy) * z + f * y, z * (B - ys))
same("y_s >= -B plane", (B + cy) * z - f * y, z * (ys + B))

# The crossing t = s_a / (s_a - s_b) of a plane a.p + d lies on the plane, and a crossing
# on the band plane x_s = B projects to B exactly.
a = sp.symbols("a0:3", real=True)
d = sp.Symbol("d", real=True)
p = sp.symbols("p0:3", real=True)
q = sp.symbols("q0:3", real=True)
value = lambda r: sum(ai * ri for ai, ri in zip(a, r)) + d  # noqa: E731
t = value(p) / (value(p) - value(q))
point = [pi + t * (qi - pi) for pi, qi in zip(p, q)]
same("crossing lies on the plane", sp.together(value(point)), 0)
pz = sp.Symbol("pz", positive=True)
qz = sp.Symbol("qz", positive=True)
px, qx = sp.symbols("px qx", real=True)
band = lambda r: (B - cx) * r[2] - f * r[0]  # noqa: E731
tb = band((px, 0, pz)) / (band((px, 0, pz)) - band((qx, 0, qz)))
cross = [px + tb * (qx - px), pz + tb * (qz - pz)]
same("band crossing projects to B", sp.together(cx + f * cross[0] / cross[1]), B)

# In doubles, as plane_crossing and project compute it (Python's floats are IEEE doubles,
# no fused multiply-add), the crossing is more than a few units in the last place of B
# from B: the text's example lands 554 of them inside, about 6e-8 px.
import math  # noqa: E402


def band_crossing_xs(x_in, z_in, x_out, z_out, focal, centre, band):
    normal = (-focal, band - centre)  # the plane (B - c_x) z - f x >= 0, in (x, z)
    s_in = normal[0] * x_in + normal[1] * z_in
    s_out = normal[0] * x_out + normal[1] * z_out
    assert s_in >= 0.0 > s_out
    denominator = normal[0] * (x_in - x_out) + normal[1] * (z_in - z_out)
    if not denominator > 0.0:
        denominator = s_in - s_out
    t_hat = min(max(s_in / denominator, 0.0), 1.0)
    x_hat, z_hat = x_in + t_hat * (x_out - x_in), z_in + t_hat * (z_out - z_in)
    return centre + focal * x_hat / z_hat


xs_example = band_crossing_xs(30.0, 95.0, 70.0, 0.13, 1024.0, 640.0, 2.0**19)
ulps_off = (xs_example - 2.0**19) / math.ulp(2.0**19)
holds(f"the band crossing lands 554 units in the last place inside B ({ulps_off})",
      ulps_off == -554)
holds("that is about 6e-8 px", 5e-8 < abs(xs_example - 2.0**19) < 7e-8)

# The band: half of chapter 2's exact range 2^20 px, far beyond the largest image side.
holds("B = 2^19 is half the exact range", sp.Integer(2)**19 * 2 == sp.Integer(2)**20)
holds("B is beyond the largest image side 8192", sp.Integer(2)**19 > 8192)
# A unit in the last place of a double near 2^19 px is 2^-33 px.
same("one ulp at 2^19", sp.Integer(2)**(19 - 52), sp.Integer(2)**-33)
holds("that is about 1e-10 px", sp.Rational(1, 10**10) < sp.Integer(2)**-33 < sp.Rational(2, 10**10))

# @eq:scene-far-row: at H = 48 and 90 degrees f = 24; a floor y = -1 lands on 24 + 24/z.
H, zz = sp.Integer(48), sp.Symbol("zz", positive=True)
focal = (H / 2) / sp.tan(sp.pi / 4)
same("f = 24", focal, 24)
row = sp.Integer(24) - focal * (-1) / zz
same("floor row", row, 24 + 24 / zz)
same("far = 10 ends at 26.4", row.subs(zz, 10), sp.Rational(264, 10))
depth_at = lambda yc: sp.solve(sp.Eq(row, yc), zz)[0]  # noqa: E731
same("row 25's centre sees depth 16", depth_at(sp.Rational(51, 2)), 16)
same("row 26's centre sees depth 9.6", depth_at(sp.Rational(53, 2)), sp.Rational(48, 5))
# The sides x = +-2 at depth 9.6 land on 32 +- 48/9.6 = 27 and 37: centres 27.5 .. 36.5.
same("left side at row 26", 32 - focal * 2 / sp.Rational(48, 5), 27)
same("right side at row 26", 32 + focal * 2 / sp.Rational(48, 5), 37)

finish("ch07_clipping")
