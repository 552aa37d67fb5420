#!/usr/bin/env python3
"""Bakes ambient occlusion or a lightmap of an OBJ mesh (its own UVs and normals) with Blender
Cycles (PyPI `bpy==5.0.1`, Python 3.11), for `scripts/cycles_bake_compare.sh`.

Usage: cycles_bake.py MESH.obj OUT.npy --kind ao|lightmap --res N --samples S [--threads T]
       [--seed K] [--repeat R] [--distance D] [--sun X,Y,Z,E] [--indirect --bounces B]
       [--indirect-only]

* `ao`: `bpy.ops.object.bake(type="AO")`, the world's AO distance `--distance`.
* `lightmap`: `type="DIFFUSE"` with the colour pass off, so Cycles bakes the diffuse
  lighting E/π (E the irradiance, as stagelight's `Lightmap(store: Irradiance)` writes it):
  direct light from a sun travelling along X,Y,Z with irradiance E on a facing surface (angle
  0: a hard shadow, as stagelight's `Directional`), and with `--indirect` diffuse
  interreflection of up to B bounces (stagelight's `max_depth`: the means agree with B equal
  to it); `--indirect-only` leaves the direct pass out. The world is black.
Where bakes are compared texel by texel (docs/baking.md): Cycles' one-sample direct bake
equals stagelight's texel-centre value (`texel_samples: 1`) from 256² on; with more samples
Cycles averages over part of the texel (it differs at shadow edges), and at 32²–128² on this
mesh its one sample lies elsewhere in the texel.
The material is a Diffuse BSDF of the rock's albedo: Cycles evaluates the surface shader at
every bake sample, and with the default Principled BSDF the AO bake took 1.3× as long.

Writes the baked texture as a float32 numpy array (rows bottom-up, as Blender stores images;
channels RGBA, −1 where Cycles baked nothing) and prints one line per bake:
`cycles_bake_seconds S user U sys Y` (wall and CPU seconds of the `bpy.ops.object.bake` call:
Cycles' scene sync, its BVH (Embree) and the texels)."""
import argparse
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_common import black_world, cycles_settings  # noqa: E402

ALBEDO = (0.6, 0.58, 0.55)  # bake_ao.ron's "stone"


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("mesh")
    p.add_argument("out")
    p.add_argument("--kind", choices=["ao", "lightmap"], required=True)
    p.add_argument("--res", type=int, required=True)
    p.add_argument("--samples", type=int, required=True)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--distance", type=float, default=1.0e4)
    p.add_argument("--sun", default="0.4,0.6,-1,2.5")
    p.add_argument("--indirect", action="store_true")
    p.add_argument("--bounces", type=int, default=2)
    p.add_argument("--indirect-only", action="store_true")
    return p.parse_args()


def add_sun(scene, spec):
    x, y, z, irradiance = (float(v) for v in spec.split(","))
    light = bpy.data.lights.new("sun", "SUN")
    light.energy = irradiance
    light.angle = 0.0
    sun = bpy.data.objects.new("sun", light)
    # A sun shines along its local −Z.
    sun.rotation_euler = Vector((x, y, z)).normalized().to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(sun)


def diffuse_material(image):
    mat = bpy.data.materials.new("stone")
    mat.use_nodes = True
    tree = mat.node_tree
    for n in [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"]:
        tree.nodes.remove(n)
    output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*ALBEDO, 1.0)
    tree.links.new(diffuse.outputs[0], output.inputs[0])
    node = tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    tree.nodes.active = node
    return mat


def setup(a):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.wm.obj_import(filepath=a.mesh, forward_axis="Y", up_axis="Z")
    obj = bpy.context.selected_objects[0]
    scene = bpy.context.scene
    cycles_settings(scene, a.samples, a.seed, a.bounces, a.threads)
    black_world(scene).light_settings.distance = a.distance
    if a.kind == "lightmap":
        add_sun(scene, a.sun)
    image = bpy.data.images.new("baked", a.res, a.res, alpha=True, float_buffer=True)
    obj.data.materials.clear()
    obj.data.materials.append(diffuse_material(image))
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bake = scene.render.bake
    bake.margin = 0
    bake.use_clear = False
    bake.use_pass_direct = not a.indirect_only
    bake.use_pass_indirect = a.indirect
    bake.use_pass_color = False
    return image


def unbaked(image, res):
    """Fills the image with −1, which no baked texel holds (AO and E/π are ≥ 0)."""
    image.pixels.foreach_set(np.full(res * res * 4, -1.0, dtype=np.float32))


def main():
    a = parse()
    image = setup(a)
    kind = {"ao": "AO", "lightmap": "DIFFUSE"}[a.kind]
    for _ in range(a.repeat):
        unbaked(image, a.res)
        t0, c0 = time.perf_counter(), os.times()
        bpy.ops.object.bake(type=kind)
        c1 = os.times()
        print("cycles_bake_seconds %.4f user %.2f sys %.2f" % (
            time.perf_counter() - t0, c1.user - c0.user, c1.system - c0.system), flush=True)
    px = np.empty(a.res * a.res * 4, dtype=np.float32)
    image.pixels.foreach_get(px)
    np.save(a.out, px.reshape(a.res, a.res, 4))


if __name__ == "__main__":
    main()
