#!/usr/bin/env python3
"""The numpy side of `scripts/cycles_bake_compare.sh`.

  bake_compare.py obj BAKED.ply OUT.obj
      turns the PLY copy of a mesh that a per-vertex bake writes (positions, normals, s t)
      into an OBJ with the same vertices, normals and UVs, so that stagelight and Blender
      bake exactly one mesh.
  bake_compare.py error TEST REFERENCE
      relMSE (mean of (x−r)²/(r²+0.01), stagelight's sweep metric), MSE and means over the
      texels baked in both, and how many of them agree to within 1e-4. TEST and REFERENCE
      are `.npy` arrays from `cycles_bake.py` (rows bottom-up, RGBA, −1 where Cycles baked
      nothing) or stagelight EXRs `<instance>_ao.exr` / `<instance>_lightmap.exr` (rows
      top-down) with the mask PNG a bake with `mask: true` writes beside them
      (`<instance>_mask.png`: where the texel was baked). Lightmaps are compared as E/π, the
      value Cycles' diffuse bake without its colour pass writes."""
import os
import struct
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import exr_f32  # noqa: E402


def ply_to_obj(ply, obj):
    buf = open(ply, "rb").read()
    end = buf.index(b"end_header\n") + len(b"end_header\n")
    header = buf[:end].decode().split("\n")
    props = [ln.split()[-1] for ln in header if ln.startswith("property") and "list" not in ln]
    nv = int(next(ln for ln in header if ln.startswith("element vertex")).split()[2])
    nf = int(next(ln for ln in header if ln.startswith("element face")).split()[2])
    kinds = {"float": "<f4", "uchar": "u1"}
    types = [ln.split()[1] for ln in header if ln.startswith("property") and "list" not in ln]
    vdt = np.dtype([(n, kinds[t]) for n, t in zip(props, types)])
    v = np.frombuffer(buf, dtype=vdt, count=nv, offset=end)
    fdt = np.dtype([("n", "u1"), ("i", "<u4", 3)])
    f = np.frombuffer(buf, dtype=fdt, count=nf, offset=end + nv * vdt.itemsize)
    if not (f["n"] == 3).all():
        sys.exit("%s: only triangles are expected" % ply)
    with open(obj, "w") as out:
        out.write("# %d vertices, %d triangles from %s\n" % (nv, nf, os.path.basename(ply)))
        for x, y, z in zip(v["x"], v["y"], v["z"]):
            out.write("v %.9g %.9g %.9g\n" % (x, y, z))
        for s, t in zip(v["s"], v["t"]):
            out.write("vt %.9g %.9g\n" % (s, t))
        for x, y, z in zip(v["nx"], v["ny"], v["nz"]):
            out.write("vn %.9g %.9g %.9g\n" % (x, y, z))
        for a, b, c in f["i"] + 1:
            out.write("f %d/%d/%d %d/%d/%d %d/%d/%d\n" % (a, a, a, b, b, b, c, c, c))


def png_gray(path):
    """An 8-bit grey or RGB(A) PNG (as stagelight writes masks) as a bool array, rows
    top-down: True where the value is not 0."""
    buf = open(path, "rb").read()
    pos, idat, w = 8, b"", 0
    while pos < len(buf):
        (n,), kind = struct.unpack(">I", buf[pos:pos + 4]), buf[pos + 4:pos + 8]
        body = buf[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, color = struct.unpack(">IIBB", body[:10])
            if depth != 8:
                sys.exit("%s: 8-bit PNG expected" % path)
            bpp = {0: 1, 2: 3, 4: 2, 6: 4}[color]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + w * bpp)
    rows = np.zeros((h, w * bpp), dtype=np.int32)
    for y in range(h):
        ft, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        prev = rows[y - 1] if y else np.zeros(w * bpp, dtype=np.int32)
        if ft == 0:
            cur = line
        elif ft == 2:
            cur = (line + prev) & 255
        else:
            cur = np.zeros(w * bpp, dtype=np.int32)
            for x in range(w * bpp):
                a = cur[x - bpp] if x >= bpp else 0
                b = prev[x]
                c = prev[x - bpp] if x >= bpp else 0
                if ft == 1:
                    pred = a
                elif ft == 3:
                    pred = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + pred) & 255
        rows[y] = cur
    return rows.reshape(h, w, bpp)[:, :, 0] != 0


def load(path):
    """(values, baked mask), rows top-down."""
    if path.endswith(".npy"):
        a = np.load(path)[::-1]
        return a[:, :, 0].astype(np.float64), a[:, :, 0] >= 0.0
    value = exr_f32.load_rgb(path)[:, :, 0]
    for suffix, scale in (("_ao.exr", 1.0), ("_lightmap.exr", 1.0 / np.pi)):
        if path.endswith(suffix):
            return value * scale, png_gray(path[: -len(suffix)] + "_mask.png")
    sys.exit("%s: an `_ao.exr` or `_lightmap.exr` bake expected" % path)


def error(test, ref):
    (x, mx), (r, mr) = load(test), load(ref)
    m = mx & mr
    d = x[m] - r[m]
    print("relMSE %.4e  MSE %.4e  mean test %.6f  mean ref %.6f  texels %d (test %d, ref %d, "
          "within 1e-4: %d)" % (np.mean(d * d / (r[m] * r[m] + 1e-2)), np.mean(d * d), x[m].mean(),
                                r[m].mean(), m.sum(), mx.sum(), mr.sum(), (abs(d) < 1e-4).sum()))


def main():
    if sys.argv[1] == "obj":
        ply_to_obj(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "error":
        error(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
