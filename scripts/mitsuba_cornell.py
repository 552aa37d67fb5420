#!/usr/bin/env python3
"""Renders stagelight's Cornell box (assets/scenes/cornell_box.ron) with Mitsuba 3.

The geometry, materials, camera and emission are read from the RON files, so the two renderers
see the same scene: inline polygons are fan-triangulated exactly as stagelight does, normals are
per face, every surface is Lambertian, the light is a one-sided area emitter. Mitsuba's
`max_depth` counts path segments, stagelight's `max_depth` counts gathering vertices, so
Mitsuba gets stagelight's value + 1. Box pixel filter on both.

Usage: python3 scripts/mitsuba_cornell.py OUT.exr [--spp N] [--variant llvm_ad_rgb] [--max-depth 4]
       python3 scripts/mitsuba_cornell.py OUT.exr --sweep 1,2,4,8,16 --reference REF.exr
(the sweep renders every sample count twice, so the kernel compilation of the first run is
not timed, and prints seconds and relMSE against REF).
Needs `pip install mitsuba` (and libLLVM for the llvm variants; scalar_rgb needs nothing).
"""
import argparse
import math
import os
import re
import sys
import tempfile
import time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
SCENE = os.path.join(ROOT, "assets", "scenes", "cornell_box.ron")
GEOMETRY = os.path.join(ROOT, "assets", "scenes", "lib", "cornell_geometry.ron")
MATERIALS = os.path.join(ROOT, "assets", "scenes", "lib", "cornell_materials.ron")

NUM = r"-?[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?"


def triples(text):
    return [tuple(float(x) for x in m) for m in re.findall(
        rf"\(\s*({NUM})\s*,\s*({NUM})\s*,\s*({NUM})\s*\)", text)]


def parse_objects(text):
    """(name, vertices, polygons, material) of every inline object."""
    objects = []
    pattern = re.compile(
        r'name:\s*"([^"]+)",\s*mesh:\s*Inline\(\s*vertices:\s*\[(.*?)\],\s*'
        r'polygons:\s*\[(.*?)\],?\s*\),\s*material:\s*"([^"]+)"', re.S)
    for name, verts, polys, material in pattern.findall(text):
        polygons = [[int(i) for i in p.split(",") if i.strip()]
                    for p in re.findall(r"\[([^\[\]]*)\]", polys)]
        objects.append((name, triples(verts), polygons, material))
    return objects


def parse_materials(text):
    """name -> (albedo, emission or None)."""
    out = {}
    for line in text.splitlines():
        m = re.search(r'name:\s*"([^"]+)".*?albedo:\s*(\([^)]*\))(.*)', line)
        if not m:
            continue
        albedo = triples(m.group(2))[0]
        em = re.search(r"emission:\s*(\([^)]*\))", m.group(3))
        out[m.group(1)] = (albedo, triples(em.group(1))[0] if em else None)
    return out


def write_obj(path, vertices, polygons):
    with open(path, "w") as f:
        for v in vertices:
            f.write("v %r %r %r\n" % v)
        for p in polygons:
            for k in range(1, len(p) - 1):  # fan, as stagelight's inline meshes
                f.write("f %d %d %d\n" % (p[0] + 1, p[k] + 1, p[k + 1] + 1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("--max-depth", type=int, default=4, help="stagelight's max_depth")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--sweep", help="comma-separated sample counts to time against --reference")
    ap.add_argument("--reference", help="EXR the sweep is compared with")
    args = ap.parse_args()

    import mitsuba as mi
    mi.set_variant(args.variant)

    # The camera is in the scene, the objects in the geometry library it includes.
    scene_text = open(SCENE).read() + open(GEOMETRY).read()
    materials = parse_materials(open(MATERIALS).read())
    eye = triples(re.search(r"eye:\s*\([^)]*\)", scene_text).group(0))[0]
    target = triples(re.search(r"target:\s*\([^)]*\)", scene_text).group(0))[0]
    up = triples(re.search(r"up:\s*\([^)]*\)", scene_text).group(0))[0]
    fov = float(re.search(rf"fov_y:\s*({NUM})", scene_text).group(1))
    w, h = (int(x) for x in re.search(r"resolution:\s*\((\d+),\s*(\d+)\)", scene_text).groups())

    tmp = tempfile.mkdtemp()
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": args.max_depth + 1},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": fov,
            "to_world": mi.ScalarTransform4f().look_at(origin=eye, target=target, up=up),
            "sampler": {"type": "independent", "sample_count": args.spp, "seed": args.seed},
            "film": {"type": "hdrfilm", "width": w, "height": h, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
        },
    }
    for name, verts, polys, material in parse_objects(scene_text):
        path = os.path.join(tmp, name + ".obj")
        write_obj(path, verts, polys)
        albedo, emission = materials[material]
        shape = {"type": "obj", "filename": path, "face_normals": True,
                 "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": albedo}}}
        if emission is not None:
            shape["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": emission}}
        scene[name] = shape

    loaded = mi.load_dict(scene)
    if args.sweep:
        return sweep(mi, loaded, [int(x) for x in args.sweep.split(",")], args)
    start = time.time()
    image = mi.render(loaded, spp=args.spp)
    mi.Bitmap(image).write(args.out)
    print("rendered %s: %d spp, %s, %.2f s" % (args.out, args.spp, args.variant,
                                                time.time() - start))


def sweep(mi, loaded, counts, args):
    import numpy as np

    ref = np.array(mi.Bitmap(args.reference), dtype=np.float64)[:, :, :3]
    print("spp,seconds,relMSE")
    for spp in counts:
        mi.render(loaded, spp=spp, seed=args.seed + 1)  # compile the kernel for this size
        start = time.time()
        image = np.array(mi.render(loaded, spp=spp, seed=args.seed), dtype=np.float64)[:, :, :3]
        seconds = time.time() - start
        d = image - ref
        print("%d,%.3f,%.3e" % (spp, seconds, np.mean(d * d / (ref * ref + 1e-2))))


if __name__ == "__main__":
    sys.exit(main())
