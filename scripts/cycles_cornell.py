#!/usr/bin/env python3
"""Renders stagelight's Cornell box (assets/scenes/cornell_box.ron) with Blender Cycles
(PyPI `bpy==5.0.1`, Python 3.11), for `scripts/cycles_cornell_compare.sh`.

The geometry, materials, camera and emission are read from the RON files by
`mitsuba_cornell.py`'s parsers, so the renderers see one scene: inline polygons
fan-triangulated as stagelight does them, flat shading, Lambertian (Diffuse BSDF) surfaces,
the light a one-sided emitter (its back faces are only diffuse, and Cycles samples only its
front). Box pixel filter one pixel wide, no adaptive sampling, no denoising, no clamping, no
filter on glossy paths. Cycles counts bounces after the camera hit, stagelight's `max_depth`
counts shading vertices including it, so Cycles' `max_bounces` is the scene's `max_depth` − 1
(with it the 64-spp means agree to 0.03 %; with `max_depth` they are 1–2 % brighter).

Usage: cycles_cornell.py OUT.exr --spp N [--threads T] [--seed K] [--repeat R]
Prints `cycles_render_seconds S` per render (the `bpy.ops.render.render` call: Cycles' scene
sync, its BVH and the samples); writes the last render as a 32-bit float EXR."""
import argparse
import math
import os
import re
import sys
import time

import bpy
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_common import black_world, cycles_settings  # noqa: E402
from mitsuba_cornell import (  # noqa: E402
    GEOMETRY, MATERIALS, NUM, SCENE, parse_materials, parse_objects, triples)


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--spp", type=int, required=True)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--repeat", type=int, default=1)
    return p.parse_args()


def material(name, albedo, emission):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True  # deprecated in Blender 5 (always on), needed before it
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*albedo, 1.0)
    if emission is None:
        tree.links.new(diffuse.outputs[0], out.inputs["Surface"])
        return mat
    scale = max(emission)
    light = tree.nodes.new("ShaderNodeEmission")
    light.inputs["Color"].default_value = (*[c / scale for c in emission], 1.0)
    light.inputs["Strength"].default_value = scale
    both = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(light.outputs[0], both.inputs[0])
    tree.links.new(diffuse.outputs[0], both.inputs[1])
    side = tree.nodes.new("ShaderNodeMixShader")
    backfacing = tree.nodes.new("ShaderNodeNewGeometry").outputs["Backfacing"]
    tree.links.new(backfacing, side.inputs["Fac"])
    tree.links.new(both.outputs[0], side.inputs[1])
    tree.links.new(diffuse.outputs[0], side.inputs[2])
    tree.links.new(side.outputs[0], out.inputs["Surface"])
    mat.cycles.emission_sampling = "FRONT"
    return mat


def camera(scene, text):
    eye, target, up = (Vector(triples(re.search(k + r":\s*\([^)]*\)", text).group(0))[0])
                       for k in ("eye", "target", "up"))
    fov = float(re.search(rf"fov_y:\s*({NUM})", text).group(1))
    w, h = (int(x) for x in re.search(r"resolution:\s*\((\d+),\s*(\d+)\)", text).groups())
    back = (eye - target).normalized()  # the camera looks down its −Z
    right = up.cross(back).normalized()
    true_up = back.cross(right)
    data = bpy.data.cameras.new("cam")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov)
    data.clip_start, data.clip_end = 1e-3, 1e5
    cam = bpy.data.objects.new("cam", data)
    m = Matrix.Identity(4)
    for row in range(3):
        m[row][0], m[row][1], m[row][2], m[row][3] = right[row], true_up[row], back[row], eye[row]
    cam.matrix_world = m
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100


def setup(a):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    text = open(SCENE).read() + open(GEOMETRY).read()
    materials = parse_materials(open(MATERIALS).read())
    for name, verts, polys, mat_name in parse_objects(text):
        tris = [(p[0], p[k], p[k + 1]) for p in polys for k in range(1, len(p) - 1)]
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata(verts, [], tris)
        mesh.materials.append(material(mat_name, *materials[mat_name]))
        scene.collection.objects.link(bpy.data.objects.new(name, mesh))
    camera(scene, text)
    black_world(scene)
    max_depth = int(re.search(r"max_depth:\s*(\d+)", text).group(1))
    c = cycles_settings(scene, a.spp, a.seed, max_depth - 1, a.threads)
    c.blur_glossy = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.use_persistent_data = False
    s = scene.render.image_settings
    s.file_format, s.color_depth, s.exr_codec = "OPEN_EXR", "32", "ZIP"
    s.color_mode = "RGB"
    scene.render.filepath = os.path.abspath(a.out)
    scene.render.use_file_extension = False


def main():
    a = parse()
    setup(a)
    for _ in range(a.repeat):
        t0, c0 = time.perf_counter(), os.times()
        bpy.ops.render.render(write_still=True)
        c1 = os.times()
        print("cycles_render_seconds %.4f user %.2f sys %.2f" % (
            time.perf_counter() - t0, c1.user - c0.user, c1.system - c0.system), flush=True)


if __name__ == "__main__":
    main()
