#!/usr/bin/env python3
"""Writes one mesh as OBJ (by hand) and as PLY (by the third-party `plyfile` writer:
ASCII, binary little-endian, binary big-endian) into tests/fixtures/meshes/, for the
round-trip test in tests/mesh_files.rs (the four files must render byte-identical).

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install plyfile
    /tmp/venv/bin/python scripts/make_mesh_fixtures.py

The mesh: a box of six quads (24 vertices, each with a normal and a texture coordinate)
and an octagonal lid (a fan of 6 triangles), at coordinates that are not exact in binary
(0.1, 0.3, …), so any f32 rounding before the loader's own would show. Each OBJ vertex
has its own `v/vt/vn` triple in order of first use, so both formats list the same
vertices in the same order.
"""

import math
import os

import numpy as np
from plyfile import PlyData, PlyElement

OUT = os.path.join(os.path.dirname(__file__), "..", "tests", "fixtures", "meshes")

vertices = []  # (position, normal, uv, colour)
faces = []


def quad(corners, normal):
    start = len(vertices)
    for k, p in enumerate(corners):
        uv = [(0.1, 0.1), (0.9, 0.1), (0.9, 0.9), (0.1, 0.9)][k]
        vertices.append((p, normal, uv, (200, 40 * k, 10)))
    faces.append(list(range(start, start + 4)))


x0, x1, y0, y1, z0, z1 = 0.3, 1.3, 0.1, 0.7, -0.3, 0.9
quad([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1))
quad([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1))
quad([(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)], (1, 0, 0))
quad([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0))
quad([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0))
# The lid: an octagon above the box.
start = len(vertices)
for k in range(8):
    a = 2 * math.pi * k / 8
    p = (0.8 + 0.45 * math.cos(a), y1 + 0.2, 0.3 - 0.45 * math.sin(a))
    vertices.append((p, (0.0, 1.0, 0.0), (0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a)), (9, 9, 9)))
faces.append(list(range(start, start + 8)))

with open(os.path.join(OUT, "box.obj"), "w") as f:
    f.write("# box.obj: written by scripts/make_mesh_fixtures.py (same mesh as box_*.ply)\n")
    for p, _, _, _ in vertices:
        f.write("v %r %r %r\n" % p)
    for _, _, uv, _ in vertices:
        f.write("vt %r %r\n" % uv)
    for _, n, _, _ in vertices:
        f.write("vn %r %r %r\n" % tuple(float(c) for c in n))
    for face in faces:
        f.write("f " + " ".join("%d/%d/%d" % (i + 1, i + 1, i + 1) for i in face) + "\n")

for name, text, byte_order, uv in [
    ("box_ascii.ply", True, "=", ("s", "t")),
    ("box_le.ply", False, "<", ("u", "v")),
    ("box_be.ply", False, ">", ("texture_u", "texture_v")),
]:
    vertex = np.array(
        [(*p, *n, *t, *c) for p, n, t, c in vertices],
        dtype=[("x", "f8"), ("y", "f8"), ("z", "f8"), ("nx", "f4"), ("ny", "f4"), ("nz", "f4"),
               (uv[0], "f4"), (uv[1], "f4"), ("red", "u1"), ("green", "u1"), ("blue", "u1")],
    )
    face = np.array([(np.array(fc, dtype="i4"),) for fc in faces], dtype=[("vertex_indices", object)])
    data = PlyData(
        [
            PlyElement.describe(vertex, "vertex"),
            PlyElement.describe(face, "face", val_types={"vertex_indices": "i4"}, len_types={"vertex_indices": "u1"}),
        ],
        text=text,
        byte_order=byte_order,
        comments=["written by plyfile through scripts/make_mesh_fixtures.py"],
    )
    data.write(os.path.join(OUT, name))
