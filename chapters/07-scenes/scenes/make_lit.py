#!/usr/bin/env python3
"""Writes lit.toml, chapter 7's lit scene: a textured torus of quads split into triangles,
with smooth normals computed by the loader, on a floor, beside a box, under a directional
and a point light. Usage: python3 make_lit.py > lit.toml
The torus has its axis along y: a point at angles (a, b) is
  centre + (R + r cos b) (cos a, 0, sin a) + r sin b (0, 1, 0),
and its outward normal is cos b (cos a, 0, sin a) + sin b (0, 1, 0)."""
import math

R, r = 1.0, 0.42  # ring and tube radii, world units
RING, TUBE = 40, 20  # quads around the ring and around the tube
CENTRE = (0.0, 0.62, 1.0)
TEXELS_U, TEXELS_V = 16 * 8, 6 * 8  # 16 x 6 squares of 8 texels


def point(i, j):
    a, b = 2 * math.pi * i / RING, 2 * math.pi * j / TUBE
    s = R + r * math.cos(b)
    return (CENTRE[0] + s * math.cos(a), CENTRE[1] + r * math.sin(b),
            CENTRE[2] + s * math.sin(a))


def outward(i, j):
    a, b = 2 * math.pi * i / RING, 2 * math.pi * j / TUBE
    return (math.cos(b) * math.cos(a), math.sin(b), math.cos(b) * math.sin(a))


def sub(p, q):
    return tuple(x - y for x, y in zip(p, q))


def cross(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def dot(p, q):
    return sum(x * y for x, y in zip(p, q))


positions, uvs = [], []
for i in range(RING):
    for j in range(TUBE):
        quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
        for tri in ([quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]):
            p = [point(*c) for c in tri]
            # Front faces run counter-clockwise seen from outside; in the left-handed
            # world that makes (p2 - p0) x (p1 - p0) point outward (lighting.hpp).
            n = cross(sub(p[2], p[0]), sub(p[1], p[0]))
            mid = (i + 0.5, j + 0.5)
            if dot(n, outward(*mid)) < 0:
                tri = [tri[0], tri[2], tri[1]]
            for c in tri:
                # The seam vertices (i = RING, j = TUBE) are at the same position as
                # i = 0, j = 0, so the smooth normals join across the seam.
                positions.append(point(c[0] % RING, c[1] % TUBE))
                uvs.append((TEXELS_U * c[0] / RING, TEXELS_V * c[1] / TUBE))


def fmt(v):
    return "[" + ", ".join(f"{x:.9g}" for x in v) + "]"


print(f"""# Chapter 7's lit scene, written by make_lit.py (do not edit: run
#   python3 make_lit.py > lit.toml). A textured torus of {len(positions) // 3} triangles
# with smooth normals and a Blinn-Phong highlight, lit per pixel; a box lit per vertex
# with face normals; a floor, whose corners turn so that its normal points up. A directional light and a point light; the torus hides
# parts of itself, so `depth = "auto"` turns the depth stage on.
[image]
width = 320
height = 240
background = [0.05, 0.06, 0.09]

[camera]
projection = "perspective"
fov = 50
position = [0.0, 2.9, -3.3]
target = [0.0, 0.45, 1.0]
near = 0.1

[render]
precision = "double"
mapper = "auto"
budget = 0.5
depth = "auto"
shading = "phong"
ambient = [0.3, 0.3, 0.35]

[[light]]
type = "directional"
direction = [0.5, -1.0, 0.6]
colour = [1.0, 0.96, 0.9]
intensity = 0.8

[[light]]
type = "point"
position = [-1.8, 1.6, -0.4]
colour = [0.55, 0.7, 1.0]
intensity = 2.5

[textures.checker]
kind = "checkerboard"
size = [16, 16]
square = 8

[[mesh]]
name = "floor"
primitive = "quad"
colour = [0.7, 0.7, 0.7]
corners = [[-3.0, 0.0, -1.5], [3.0, 0.0, -1.5], [3.0, 0.0, 4.5], [-3.0, 0.0, 4.5]]

[[mesh]]
name = "box lit per vertex"
primitive = "box"
colour = [0.9, 0.45, 0.2]
centre = [1.9, 0.35, 2.2]
size = [0.7, 0.7, 0.7]
shading = "gouraud"
specular = [0.3, 0.3, 0.3]
shininess = 16

[[mesh]]
name = "torus"
primitive = "triangles"
texture = "checker"
colour = [0.95, 0.9, 0.8]
normals = "smooth"
specular = [0.6, 0.6, 0.6]
shininess = 60
cull = "back"
positions = [""")
for p in positions:
    print("  " + fmt(p) + ",")
print("]\nuv = [")
for uv in uvs:
    print("  " + fmt(uv) + ",")
print("]")
