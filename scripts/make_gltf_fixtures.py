#!/usr/bin/env python3
"""Writes the glTF test files (tests/fixtures/gltf/) and the glTF example asset
(assets/gltf/lightmap_room.glb) with the third-party writer `pygltflib`.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pygltflib numpy
    /tmp/venv/bin/python scripts/make_gltf_fixtures.py

Files:
- box.glb, box_embedded.gltf (base64 buffer), box_external.gltf + box.bin: the box of
  tests/fixtures/meshes/box.obj (same vertices, normals, triangles in the OBJ's fan order),
  so OBJ, PLY and glTF render byte-identical (tests/it/gltf.rs).
- hierarchy.glb: one triangle mesh used by three child nodes of a translated parent, a
  perspective camera and a KHR_lights_punctual point light.
- two_uv_sets.glb: a unit quad whose TEXCOORD_1 is TEXCOORD_0 scaled by ½ (lightmap UVs).
- bad files: truncated.glb (box.glb cut short), wrong_magic.glb, bad_accessor.glb (an
  accessor reading past its buffer view), missing_buffer.gltf (a buffer file that does not
  exist), points.glb (a POINTS primitive), bad_index.glb (an index past the vertex count).
- normal_map.glb, emissive.glb, mask.glb: material textures embedded as PNG (written
  here with zlib): a quad with a tangent-space normal texture (scale 1.5; left half tilted
  along +u, right half toward the image's top), a quad with an emissive texture
  (emissiveFactor ½, KHR_materials_emissive_strength 1.5), and a card with an alpha
  cut-out (alphaMode MASK, cutoff ½: alpha 0 on the left half, 1 on the right) in front of
  a wall, lit at 45° by a directional light (tests/it/gltf_materials.rs);
  blend.glb: a black mirror card with texture alpha 64/255 (alphaMode BLEND) in front of
  the white default environment; missing_texture.gltf: a normal texture whose image file
  does not exist; missing_texture.glb: a base colour texture whose image file ("bricks")
  does not exist; bad_image.glb: an embedded image ("garbage") that is not an image.
- colours.glb: four quads side by side drawn with one polished metal material (base colour
  factor (0.8, 0.6, 0.5), metallic 1, roughness 0) in the white default environment; three
  carry COLOR_0 as float vec3, normalised u8 vec4 and normalised u16 vec3, the fourth none.
- tangents.glb: three quads side by side with the same uv layout and one uniform normal
  texture (128, 192, 255), "green up"; their TANGENT is +x (w = +1), +x (w = −1), +y
  (w = +1). bad_tangent.glb (a TANGENT w of 0.5) and bad_colour.glb (COLOR_0 of unsigned
  bytes without `normalized`) are malformed.
- nan_position.glb: a quad whose POSITION holds a NaN (vertex 3; the accessor's min/max
  finite), refused with the accessor and vertex.
- loose_vertices.glb: an L of a floor and a wall quad (no TEXCOORD_1, so it bakes per
  vertex) plus vertex 8 at vertex 2's position used only by the degenerate triangle
  (8, 8, 1), and vertex 9 near vertex 6 used by no triangle (tests/it/vertex_bake.rs).
- assets/gltf/lightmap_room.glb: a floor, two walls and a box, each with TEXCOORD_1 laid out
  as unique, non-overlapping lightmap charts, a point light (KHR_lights_punctual) and a
  camera; baked by `stagelight bake assets/gltf/lightmap_room.glb --write-gltf` (README).
"""

import math
import os
import struct
import zlib

import numpy as np
import pygltflib as g

ROOT = os.path.join(os.path.dirname(__file__), "..")
OUT = os.path.join(ROOT, "tests", "fixtures", "gltf")
ASSETS = os.path.join(ROOT, "assets", "gltf")


class Builder:
    """Accumulates one binary buffer and its views/accessors."""

    def __init__(self):
        self.gltf = g.GLTF2(asset=g.Asset(version="2.0", generator="scripts/make_gltf_fixtures.py"))
        self.blob = bytearray()

    def view(self, data, target=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        offset = len(self.blob)
        self.blob += data
        self.gltf.bufferViews.append(g.BufferView(buffer=0, byteOffset=offset, byteLength=len(data), target=target))
        return len(self.gltf.bufferViews) - 1

    def accessor(self, array, kind, component, target=None, bounds=False):
        array = np.ascontiguousarray(array)
        view = self.view(array.tobytes(), target)
        acc = g.Accessor(bufferView=view, componentType=component, count=len(array), type=kind)
        if bounds:
            acc.min = [float(x) for x in array.min(axis=0)]
            acc.max = [float(x) for x in array.max(axis=0)]
        self.gltf.accessors.append(acc)
        return len(self.gltf.accessors) - 1

    def mesh(self, name, positions, normals, uv0, triangles, uv1=None, material=None, mode=g.TRIANGLES):
        attrs = g.Attributes(
            POSITION=self.accessor(np.array(positions, np.float32), g.VEC3, g.FLOAT, g.ARRAY_BUFFER, True),
            NORMAL=self.accessor(np.array(normals, np.float32), g.VEC3, g.FLOAT, g.ARRAY_BUFFER),
            TEXCOORD_0=self.accessor(np.array(uv0, np.float32), g.VEC2, g.FLOAT, g.ARRAY_BUFFER),
        )
        if uv1 is not None:
            attrs.TEXCOORD_1 = self.accessor(np.array(uv1, np.float32), g.VEC2, g.FLOAT, g.ARRAY_BUFFER)
        indices = self.accessor(np.array(triangles, np.uint16).reshape(-1), g.SCALAR, g.UNSIGNED_SHORT, g.ELEMENT_ARRAY_BUFFER)
        self.gltf.meshes.append(g.Mesh(name=name, primitives=[g.Primitive(attributes=attrs, indices=indices, material=material, mode=mode)]))
        return len(self.gltf.meshes) - 1

    def node(self, **kw):
        self.gltf.nodes.append(g.Node(**kw))
        return len(self.gltf.nodes) - 1

    def finish(self, roots):
        self.gltf.scenes.append(g.Scene(nodes=roots))
        self.gltf.scene = 0
        self.gltf.buffers.append(g.Buffer(byteLength=len(self.blob)))
        self.gltf.set_binary_blob(bytes(self.blob))
        return self.gltf


def box_mesh():
    """The box of scripts/make_mesh_fixtures.py: (positions, normals, uvs, triangles)."""
    vertices, faces = [], []

    def quad(corners, normal):
        start = len(vertices)
        for k, p in enumerate(corners):
            uv = [(0.1, 0.1), (0.9, 0.1), (0.9, 0.9), (0.1, 0.9)][k]
            vertices.append((p, normal, uv))
        faces.append(list(range(start, start + 4)))

    x0, x1, y0, y1, z0, z1 = 0.3, 1.3, 0.1, 0.7, -0.3, 0.9
    quad([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1))
    quad([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1))
    quad([(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)], (1, 0, 0))
    quad([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0))
    quad([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0))
    start = len(vertices)
    for k in range(8):
        a = 2 * math.pi * k / 8
        p = (0.8 + 0.45 * math.cos(a), y1 + 0.2, 0.3 - 0.45 * math.sin(a))
        vertices.append((p, (0.0, 1.0, 0.0), (0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a))))
    faces.append(list(range(start, start + 8)))
    triangles = [[f[0], f[k], f[k + 1]] for f in faces for k in range(1, len(f) - 1)]
    positions = [v[0] for v in vertices]
    normals = [v[1] for v in vertices]
    # glTF's v grows downwards: the reader flips it back.
    uvs = [(v[2][0], 1.0 - v[2][1]) for v in vertices]
    return positions, normals, uvs, triangles


def write_box():
    b = Builder()
    b.mesh("box", *box_mesh())
    b.node(name="box", mesh=0)
    gltf = b.finish([0])
    gltf.save_binary(os.path.join(OUT, "box.glb"))
    gltf.convert_buffers(g.BufferFormat.DATAURI)
    gltf.save_json(os.path.join(OUT, "box_embedded.gltf"))
    b = Builder()
    b.mesh("box", *box_mesh())
    b.node(name="box", mesh=0)
    gltf = b.finish([0])
    gltf.buffers[0].uri = "box.bin"
    with open(os.path.join(OUT, "box.bin"), "wb") as f:
        f.write(bytes(b.blob))
    gltf._glb_data = None
    gltf.save_json(os.path.join(OUT, "box_external.gltf"))


def triangle():
    return ([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 0, 1)] * 3, [(0, 1), (1, 1), (0, 0)], [[0, 1, 2]])


def write_hierarchy():
    b = Builder()
    b.mesh("tri", *triangle())
    children = [b.node(name=n, mesh=0, translation=[x, 0.0, 0.0]) for n, x in (("a", -2.0), ("b", 0.0), ("c", 2.0))]
    parent = b.node(name="parent", children=children, translation=[0.0, 0.0, -5.0])
    b.gltf.cameras.append(g.Camera(name="view", type="perspective", perspective=g.Perspective(yfov=0.8, znear=0.1, aspectRatio=2.0)))
    cam = b.node(name="eye", camera=0, translation=[0.0, 0.5, 3.0])
    b.gltf.extensionsUsed = ["KHR_lights_punctual"]
    b.gltf.extensions = {"KHR_lights_punctual": {"lights": [{"name": "lamp", "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 683.0}]}}
    lamp = b.node(name="lamp_node", translation=[0.0, 3.0, 0.0], extensions={"KHR_lights_punctual": {"light": 0}})
    b.finish([parent, cam, lamp]).save_binary(os.path.join(OUT, "hierarchy.glb"))


def write_two_uv_sets():
    b = Builder()
    p = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    n = [(0, 0, 1)] * 4
    uv0 = [(0, 1), (1, 1), (1, 0), (0, 0)]
    uv1 = [(u * 0.5, 0.5 + v * 0.5) for u, v in uv0]
    b.mesh("quad", p, n, uv0, [[0, 1, 2], [0, 2, 3]], uv1=uv1)
    b.node(name="quad", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "two_uv_sets.glb"))


def write_bad_files():
    with open(os.path.join(OUT, "box.glb"), "rb") as f:
        box = f.read()
    with open(os.path.join(OUT, "truncated.glb"), "wb") as f:
        f.write(box[: len(box) // 2])
    with open(os.path.join(OUT, "wrong_magic.glb"), "wb") as f:
        f.write(b"glTX" + box[4:])
    # An accessor reading past its view: POSITION claims 1000 vertices.
    b = Builder()
    b.mesh("tri", *triangle())
    b.gltf.accessors[0].count = 1000
    b.node(name="tri", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "bad_accessor.glb"))
    # An index past the vertex count.
    b = Builder()
    b.mesh("tri", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 0, 1)] * 3, [(0, 0)] * 3, [[0, 1, 7]])
    b.node(name="tri", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "bad_index.glb"))
    # A POINTS primitive.
    b = Builder()
    b.mesh("dots", *triangle(), mode=g.POINTS)
    b.node(name="dots", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "points.glb"))
    # A buffer file that does not exist.
    b = Builder()
    b.mesh("tri", *triangle())
    b.node(name="tri", mesh=0)
    gltf = b.finish([0])
    gltf.buffers[0].uri = "nowhere.bin"
    gltf._glb_data = None
    gltf.save_json(os.path.join(OUT, "missing_buffer.gltf"))


def write_vertex_bake_edges():
    b = Builder()
    b.mesh("quad", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (float("nan"), 1, 0)], [(0, 0, 1)] * 4, [(0, 0)] * 4, [[0, 1, 2], [0, 2, 3]])
    b.gltf.accessors[0].min = [0.0, 0.0, 0.0]
    b.gltf.accessors[0].max = [1.0, 1.0, 0.0]
    b.node(name="quad", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "nan_position.glb"))
    b = Builder()
    floor = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0)]
    wall = [(0, 0, 0), (0, 2, 0), (0, 2, 2), (0, 0, 2)]
    loose = [(2, 2, 0), (0.1, 2.2, 2.3)]
    normals = [(0, 0, 1)] * 4 + [(1, 0, 0)] * 6
    triangles = [[8, 8, 1], [0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
    b.mesh("L", floor + wall + loose, normals, [(0, 0)] * 10, triangles)
    b.node(name="L", mesh=0)
    b.finish([0]).save_binary(os.path.join(OUT, "loose_vertices.glb"))


def box_faces(b, name, lo, hi, chart_origin, chart_size, material):
    """An axis-aligned box (5 faces, no bottom) with TEXCOORD_0 per face and TEXCOORD_1 laid
    out as 5 charts in a row starting at chart_origin."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    faces = [
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1)),
        ([(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)], (1, 0, 0)),
        ([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0)),
        ([(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)], (0, 1, 0)),
    ]
    return quads(b, name, faces, chart_origin, chart_size, material)


def quads(b, name, faces, chart_origin, chart_size, material):
    p, n, uv0, uv1, tris = [], [], [], [], []
    corners = [(0, 1), (1, 1), (1, 0), (0, 0)]
    for k, (quad, normal) in enumerate(faces):
        start = len(p)
        ox, oy = chart_origin[0] + k * chart_size, chart_origin[1]
        for c, v in zip(corners, quad):
            p.append(v)
            n.append(normal)
            uv0.append(c)
            # A margin of 1/16 of a chart keeps charts apart (dilation room).
            m = chart_size / 16
            uv1.append((ox + m + c[0] * (chart_size - 2 * m), oy + m + c[1] * (chart_size - 2 * m)))
        tris += [[start, start + 1, start + 2], [start, start + 2, start + 3]]
    return b.mesh(name, p, n, uv0, tris, uv1=uv1, material=material)


def png(pixels):
    """An 8-bit PNG of `pixels` (rows top to bottom of RGB or RGBA tuples)."""
    channels = len(pixels[0][0])
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in pixels)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", len(pixels[0]), len(pixels), 8, 6 if channels == 4 else 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def quadrants(tl, tr, bl, br, size=4):
    """A size² image whose quadrants are the given colours (top-left, top-right, ...)."""
    h = size // 2
    return [[(tl if x < h else tr) if y < h else (bl if x < h else br) for x in range(size)] for y in range(size)]


def image(b, pixels, wrap=g.CLAMP_TO_EDGE):
    view = b.view(png(pixels))
    b.gltf.images.append(g.Image(bufferView=view, mimeType="image/png"))
    b.gltf.samplers.append(g.Sampler(wrapS=wrap, wrapT=wrap))
    b.gltf.textures.append(g.Texture(source=len(b.gltf.images) - 1, sampler=len(b.gltf.samplers) - 1))
    return len(b.gltf.textures) - 1


def facing_quad(b, name, half, z, material):
    """A square [−half, half]² at depth z facing +Z; glTF uv (0, 0) at its top-left corner."""
    p = [(-half, -half, z), (half, -half, z), (half, half, z), (-half, half, z)]
    uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    return b.mesh(name, p, [(0, 0, 1)] * 4, uv, [[0, 1, 2], [0, 2, 3]], material=material)


def front_camera(b, distance, yfov):
    b.gltf.cameras.append(g.Camera(name="front", type="perspective", perspective=g.Perspective(yfov=yfov, znear=0.1, aspectRatio=1.0)))
    return b.node(name="eye", camera=len(b.gltf.cameras) - 1, translation=[0.0, 0.0, distance])


def write_material_textures():
    # Normal map: left half (192, 128, 255) tilts along +u, right half (128, 192, 255)
    # toward the image's top (+y here).
    b = Builder()
    left, right = (192, 128, 255), (128, 192, 255)
    tex = image(b, quadrants(left, right, left, right))
    b.gltf.materials = [g.Material(name="bumpy", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.8, 0.8, 1.0], metallicFactor=0.0, roughnessFactor=1.0), normalTexture=g.NormalMaterialTexture(index=tex, scale=1.5))]
    mesh = facing_quad(b, "quad", 1.0, 0.0, 0)
    b.finish([b.node(name="quad", mesh=mesh), front_camera(b, 3.0, 0.8)]).save_binary(os.path.join(OUT, "normal_map.glb"))

    # Emissive texture: red, green / blue, grey quadrants; emission = ½ × 1.5 × texel.
    b = Builder()
    tex = image(b, quadrants((255, 0, 0), (0, 255, 0), (0, 0, 255), (128, 128, 128)))
    b.gltf.extensionsUsed = ["KHR_materials_emissive_strength"]
    b.gltf.materials = [g.Material(name="sign", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.0, 0.0, 0.0, 1.0], metallicFactor=0.0, roughnessFactor=1.0), emissiveTexture=g.TextureInfo(index=tex), emissiveFactor=[0.5, 0.5, 0.5], extensions={"KHR_materials_emissive_strength": {"emissiveStrength": 1.5}})]
    mesh = facing_quad(b, "quad", 1.0, 0.0, 0)
    b.finish([b.node(name="quad", mesh=mesh), front_camera(b, 3.0, 0.8)]).save_binary(os.path.join(OUT, "emissive.glb"))

    # Alpha cut-out: a black card, alpha 0 on its left half, in front of a grey wall; a
    # directional light travelling along (−1, 0, −1)/√2 (the node's −Z turned 45° about Y).
    b = Builder()
    clear, solid = (255, 255, 255, 0), (255, 255, 255, 255)
    tex = image(b, quadrants(clear, solid, clear, solid))
    b.gltf.materials = [
        g.Material(name="card", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.0, 0.0, 0.0, 1.0], baseColorTexture=g.TextureInfo(index=tex), metallicFactor=0.0, roughnessFactor=1.0), alphaMode=g.MASK, alphaCutoff=0.5),
        g.Material(name="wall", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.8, 0.8, 1.0], metallicFactor=0.0, roughnessFactor=1.0)),
    ]
    card = facing_quad(b, "card", 0.5, 0.0, 0)
    wall = facing_quad(b, "wall", 3.0, -1.0, 1)
    b.gltf.extensionsUsed = ["KHR_lights_punctual"]
    b.gltf.extensions = {"KHR_lights_punctual": {"lights": [{"name": "sun", "type": "directional", "intensity": 683.0}]}}
    a = math.radians(45) / 2
    sun = b.node(name="sun", rotation=[0.0, math.sin(a), 0.0, math.cos(a)], extensions={"KHR_lights_punctual": {"light": 0}})
    nodes = [b.node(name="card", mesh=card), b.node(name="wall", mesh=wall), front_camera(b, 4.0, 0.9), sun]
    b.finish(nodes).save_binary(os.path.join(OUT, "mask.glb"))

    # Alpha blend: a black polished metal card (it reflects nothing) whose texture alpha is
    # 64/255, in front of the white default environment (no lights).
    b = Builder()
    tex = image(b, quadrants(*[(255, 255, 255, 64)] * 4))
    b.gltf.materials = [g.Material(name="veil", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.0, 0.0, 0.0, 1.0], baseColorTexture=g.TextureInfo(index=tex), metallicFactor=1.0, roughnessFactor=0.0), alphaMode=g.BLEND)]
    mesh = facing_quad(b, "card", 1.0, 0.0, 0)
    b.finish([b.node(name="card", mesh=mesh), front_camera(b, 3.0, 0.8)]).save_binary(os.path.join(OUT, "blend.glb"))

    # A normal texture whose image file does not exist.
    b = Builder()
    b.gltf.images.append(g.Image(uri="nowhere.png"))
    b.gltf.textures.append(g.Texture(source=0))
    b.gltf.materials = [g.Material(name="lost", normalTexture=g.NormalMaterialTexture(index=0))]
    mesh = facing_quad(b, "quad", 1.0, 0.0, 0)
    gltf = b.finish([b.node(name="quad", mesh=mesh)])
    gltf.convert_buffers(g.BufferFormat.DATAURI)
    gltf.save_json(os.path.join(OUT, "missing_texture.gltf"))

    # The same in a binary file, the image named, as a base colour texture.
    b = Builder()
    b.gltf.images.append(g.Image(uri="nowhere.png", name="bricks"))
    b.gltf.textures.append(g.Texture(source=0))
    b.gltf.materials = [g.Material(name="lost", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorTexture=g.TextureInfo(index=0)))]
    mesh = facing_quad(b, "quad", 1.0, 0.0, 0)
    b.finish([b.node(name="quad", mesh=mesh)]).save_binary(os.path.join(OUT, "missing_texture.glb"))

    # An embedded image whose bytes are not an image.
    b = Builder()
    b.gltf.images.append(g.Image(bufferView=b.view(b"not a picture"), mimeType="image/png", name="garbage"))
    b.gltf.textures.append(g.Texture(source=0))
    b.gltf.materials = [g.Material(name="broken", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorTexture=g.TextureInfo(index=0)))]
    mesh = facing_quad(b, "quad", 1.0, 0.0, 0)
    b.finish([b.node(name="quad", mesh=mesh)]).save_binary(os.path.join(OUT, "bad_image.glb"))


def side_quad(b, name, x, material, extra):
    """A unit square centred at (x, 0, 0) facing +Z (glTF uv (0, 0) at its top-left corner),
    with more vertex attributes: name → (numpy array, accessor type, component type,
    normalized)."""
    p = [(x - 0.5, -0.5, 0), (x + 0.5, -0.5, 0), (x + 0.5, 0.5, 0), (x - 0.5, 0.5, 0)]
    uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    mesh = b.mesh(name, p, [(0, 0, 1)] * 4, uv, [[0, 1, 2], [0, 2, 3]], material=material)
    attrs = b.gltf.meshes[mesh].primitives[0].attributes
    for attr, (array, kind, component, normalized) in extra.items():
        acc = b.accessor(array, kind, component, g.ARRAY_BUFFER)
        b.gltf.accessors[acc].normalized = normalized or None
        setattr(attrs, attr, acc)
    return mesh


def write_vertex_attributes():
    b = Builder()
    b.gltf.materials = [g.Material(name="tinted", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.6, 0.5, 1.0], metallicFactor=1.0, roughnessFactor=0.0))]
    colours = {
        "float3": (np.array([(0.25, 0.5, 1.0)] * 4, np.float32), g.VEC3, g.FLOAT, False),
        "u8": (np.array([(255, 64, 0, 255)] * 4, np.uint8), g.VEC4, g.UNSIGNED_BYTE, True),
        "u16": (np.array([(0, 32768, 65535)] * 4, np.uint16), g.VEC3, g.UNSIGNED_SHORT, True),
    }
    nodes = []
    for k, (name, colour) in enumerate(colours.items()):
        mesh = side_quad(b, name, -1.65 + 1.1 * k, 0, {"COLOR_0": colour})
        nodes.append(b.node(name=name, mesh=mesh))
    nodes.append(b.node(name="plain", mesh=side_quad(b, "plain", 1.65, 0, {})))
    b.gltf.cameras.append(g.Camera(name="front", type="perspective", perspective=g.Perspective(yfov=0.5, znear=0.1, aspectRatio=4.0)))
    nodes.append(b.node(name="eye", camera=0, translation=[0.0, 0.0, 5.0]))
    b.finish(nodes).save_binary(os.path.join(OUT, "colours.glb"))

    b = Builder()
    tex = image(b, quadrants(*[(128, 192, 255)] * 4))
    b.gltf.materials = [g.Material(name="bumpy", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.8, 0.8, 1.0], metallicFactor=0.0, roughnessFactor=1.0), normalTexture=g.NormalMaterialTexture(index=tex, scale=1.5))]
    tangents = {"plus": (1, 0, 0, 1), "minus": (1, 0, 0, -1), "turned": (0, 1, 0, 1)}
    nodes = []
    for k, (name, t) in enumerate(tangents.items()):
        mesh = side_quad(b, name, -1.1 + 1.1 * k, 0, {"TANGENT": (np.array([t] * 4, np.float32), g.VEC4, g.FLOAT, False)})
        nodes.append(b.node(name=name, mesh=mesh))
    b.finish(nodes).save_binary(os.path.join(OUT, "tangents.glb"))

    b = Builder()
    side_quad(b, "tilted", 0.0, None, {"TANGENT": (np.array([(1, 0, 0, 0.5)] * 4, np.float32), g.VEC4, g.FLOAT, False)})
    b.finish([b.node(name="tilted", mesh=0)]).save_binary(os.path.join(OUT, "bad_tangent.glb"))
    b = Builder()
    side_quad(b, "raw", 0.0, None, {"COLOR_0": (np.array([(255, 0, 0)] * 4, np.uint8), g.VEC3, g.UNSIGNED_BYTE, False)})
    b.finish([b.node(name="raw", mesh=0)]).save_binary(os.path.join(OUT, "bad_colour.glb"))


def write_lightmap_room():
    b = Builder()
    b.gltf.materials = [
        g.Material(name="plaster", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.78, 0.72, 1.0], metallicFactor=0.0, roughnessFactor=0.9)),
        g.Material(name="painted_wood", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.7, 0.25, 0.15, 1.0], metallicFactor=0.0, roughnessFactor=0.6)),
    ]
    floor = quads(b, "floor", [([(-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2)], (0, 1, 0))], (0.0, 0.5), 0.5, 0)
    walls = quads(
        b,
        "walls",
        [
            ([(-2, 0, -2), (2, 0, -2), (2, 2.5, -2), (-2, 2.5, -2)], (0, 0, 1)),
            ([(-2, 0, 2), (-2, 0, -2), (-2, 2.5, -2), (-2, 2.5, 2)], (1, 0, 0)),
        ],
        (0.0, 0.0),
        0.5,
        0,
    )
    box = box_faces(b, "crate", (-0.4, 0.0, -0.6), (0.4, 0.8, 0.2), (0.0, 0.0), 0.2, 1)
    nodes = [b.node(name="floor", mesh=floor), b.node(name="walls", mesh=walls), b.node(name="crate", mesh=box, rotation=[0.0, math.sin(0.3), 0.0, math.cos(0.3)])]
    b.gltf.cameras.append(g.Camera(name="view", type="perspective", perspective=g.Perspective(yfov=0.9, znear=0.1, aspectRatio=4 / 3)))
    # Looking at the room from the open corner, 25° down.
    yaw, pitch = math.radians(35), math.radians(-20)
    qy = (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))
    q = (
        qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
        qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
        qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
        qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2],
    )
    nodes.append(b.node(name="eye", camera=0, translation=[3.2, 2.4, 4.2], rotation=list(q)))
    b.gltf.extensionsUsed = ["KHR_lights_punctual"]
    # 2000 cd ≈ 2.9 W/sr.
    b.gltf.extensions = {"KHR_lights_punctual": {"lights": [{"name": "bulb", "type": "point", "color": [1.0, 0.92, 0.8], "intensity": 2000.0}]}}
    nodes.append(b.node(name="bulb", translation=[0.6, 2.1, 0.6], extensions={"KHR_lights_punctual": {"light": 0}}))
    os.makedirs(ASSETS, exist_ok=True)
    b.finish(nodes).save_binary(os.path.join(ASSETS, "lightmap_room.glb"))


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_box()
    write_hierarchy()
    write_two_uv_sets()
    write_bad_files()
    write_material_textures()
    write_vertex_attributes()
    write_vertex_bake_edges()
    write_lightmap_room()
