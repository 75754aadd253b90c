#!/usr/bin/env python3
"""Writes the small glTF 2.0 files of tests/unit/gltf_loader_test.cpp and
tests/unit/gltf_animation_test.cpp (run from
this directory; the outputs are committed, so this is documentation)."""
import base64, json, struct

FLOAT, USHORT, UINT, UBYTE = 5126, 5123, 5125, 5121
POINTS, LINES, TRIANGLES, STRIP, FAN = 0, 1, 4, 5, 6


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, fmt, values, kind, ctype, count=None, **extra):
        while len(self.data) % 4:
            self.data += b"\0"
        raw = struct.pack("<" + fmt * len(values), *values)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)})
        self.data += raw
        n = {"VEC4": 4, "VEC3": 3, "SCALAR": 1}[kind]
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "type": kind,
               "count": count if count is not None else len(values) // n}
        acc.update(extra)
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def vec3(self, points):
        flat = [c for p in points for c in p]
        return self.add("f", flat, "VEC3", FLOAT,
                        min=[min(p[i] for p in points) for i in range(3)],
                        max=[max(p[i] for p in points) for i in range(3)])

    def gltf(self, **parts):
        doc = {"asset": {"version": "2.0"}}
        doc.update(parts)
        doc["buffers"] = [{"byteLength": len(self.data), "uri": "data:application/octet-stream;base64," +
                           base64.b64encode(bytes(self.data)).decode()}]
        doc["bufferViews"] = self.views
        doc["accessors"] = self.accessors
        return doc


def write(name, doc):
    with open(name, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


TRI = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]

# hierarchy.gltf: TRS and matrix nodes, parent before child; one indexed
# (ushort) triangle instanced by two nodes.
b = Builder()
pos = b.vec3(TRI)
idx = b.add("H", [0, 1, 2], "SCALAR", USHORT)
write("hierarchy.gltf", b.gltf(
    scene=0, scenes=[{"nodes": [0, 3]}],
    nodes=[
        {"translation": [10, 0, 0], "children": [1]},
        # rotate 90 degrees about z, then scale 2: (x, y) -> 2 * (-y, x)
        {"rotation": [0, 0, 0.7071067811865476, 0.7071067811865476], "scale": [2, 2, 2], "children": [2]},
        {"mesh": 0},
        # column-major matrix: translate (0, 0, -5)
        {"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1], "mesh": 0},
    ],
    meshes=[{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}]))

# modes.gltf: a non-indexed strip of 5 vertices (3 triangles), an indexed
# (ubyte) fan of 6 (4 triangles), non-indexed triangles of 6 (2), and a
# POINTS and a LINES primitive (skipped).
b = Builder()
strip = b.vec3([(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0), (2, 0, 0)])
fanp = b.vec3([(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (-1, 1, 1), (-1, 0, 1)])
fani = b.add("B", [0, 1, 2, 3, 4, 5], "SCALAR", UBYTE)
tris = b.vec3([(0, 0, 2), (1, 0, 2), (0, 1, 2), (0, 0, 3), (1, 0, 3), (0, 1, 3)])
write("modes.gltf", b.gltf(
    scenes=[{"nodes": [0]}], nodes=[{"mesh": 0}],
    meshes=[{"primitives": [
        {"attributes": {"POSITION": strip}, "mode": STRIP},
        {"attributes": {"POSITION": fanp}, "indices": fani, "mode": FAN},
        {"attributes": {"POSITION": tris}},
        {"attributes": {"POSITION": strip}, "mode": POINTS},
        {"attributes": {"POSITION": strip}, "mode": LINES},
    ]}]))

# view.gltf: camera, KHR point light, mirror and diffuse materials (the
# diffuse one with transmission, ior and specular), normals under a
# non-uniform scale.
b = Builder()
pos = b.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
nrm = b.vec3([(1, 1, 0), (1, 1, 0), (1, 1, 0)])
write("view.gltf", b.gltf(
    scenes=[{"nodes": [0, 1, 2, 3]}],
    extensionsUsed=["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                    "KHR_materials_specular"],
    extensions={"KHR_lights_punctual": {"lights": [
        {"type": "directional", "color": [1, 1, 1]},
        {"type": "point", "color": [1.0, 0.5, 0.25], "intensity": 20}]}},
    cameras=[{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
    nodes=[
        {"translation": [0, 1, 5], "camera": 0},
        {"translation": [2, 3, 4], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"scale": [2, 1, 1], "mesh": 0},
        {"translation": [0, 0, -1], "mesh": 1},
    ],
    materials=[
        {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 1.0, "roughnessFactor": 0.05}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0.0, "roughnessFactor": 0.5},
         "extensions": {
             "KHR_materials_transmission": {"transmissionFactor": 0.75},
             "KHR_materials_ior": {"ior": 1.33},
             "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1.0, 0.5, 0.25]}}},
    ],
    meshes=[{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": pos}, "material": 1}]}]))

# binary.glb: one indexed (uint) quad, 2 triangles, translated by (0, 0, 1).
b = Builder()
pos = b.vec3([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
idx = b.add("I", [0, 1, 2, 0, 2, 3], "SCALAR", UINT)
doc = b.gltf(scenes=[{"nodes": [0]}], nodes=[{"translation": [0, 0, 1], "mesh": 0}],
             meshes=[{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}])
del doc["buffers"][0]["uri"]
js = json.dumps(doc).encode()
js += b" " * ((4 - len(js) % 4) % 4)
bin_ = bytes(b.data) + b"\0" * ((4 - len(b.data) % 4) % 4)
glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_))
glb += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_
open("binary.glb", "wb").write(glb)
open("truncated.glb", "wb").write(glb[: len(glb) // 2])

# --- malformed ---------------------------------------------------------------
def simple(name, positions, indices=None, mode=None, **node):
    b = Builder()
    pos = b.vec3(positions)
    prim = {"attributes": {"POSITION": pos}}
    if indices is not None:
        prim["indices"] = b.add("H", indices, "SCALAR", USHORT)
    if mode is not None:
        prim["mode"] = mode
    doc = b.gltf(scenes=[{"nodes": [0]}], nodes=[dict(mesh=0, **node)], meshes=[{"primitives": [prim]}])
    write(name, doc)
    return doc

simple("index_out_of_range.gltf", TRI, [0, 1, 99])
simple("not_multiple_of_3.gltf", TRI, [0, 1, 2, 0])
# A NaN coordinate (no min/max: JSON cannot hold NaN).
b = Builder()
pos = b.add("f", [0, 0, 0, float("nan"), 0, 0, 0, 1, 0], "VEC3", FLOAT)
write("nan_position.gltf", b.gltf(scenes=[{"nodes": [0]}], nodes=[{"mesh": 0}],
                                  meshes=[{"primitives": [{"attributes": {"POSITION": pos}}]}]))
# An accessor claiming a million vertices in a 36-byte buffer.
doc = simple("accessor_overflow.gltf", TRI)
doc["accessors"][0]["count"] = 1000000
write("accessor_overflow.gltf", doc)
# A node cycle: 0 -> 1 -> 0.
doc = simple("node_cycle.gltf", TRI)
doc["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
write("node_cycle.gltf", doc)
# A buffer in a file that does not exist.
doc = simple("missing_buffer.gltf", TRI)
doc["buffers"][0]["uri"] = "missing.bin"
write("missing_buffer.gltf", doc)
# A point light whose colour overflows single precision (found by fuzz_gltf).
doc = simple("light_overflow.gltf", TRI)
doc["extensionsUsed"] = ["KHR_lights_punctual"]
doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1e39, 0.5, 0.25]}]}}
doc["nodes"].append({"translation": [0, 1, 5], "extensions": {"KHR_lights_punctual": {"light": 0}}})
doc["scenes"][0]["nodes"].append(1)
write("light_overflow.gltf", doc)
with open("bad_json.gltf", "w") as f:
    f.write('{"asset": {"version": "2.0"}, "nodes": [\n')


# animated.gltf: one triangle under five nodes. Node 0 is static; node 1's
# translation (LINEAR, t 0 -> 2: (0,0,0) -> (4,0,0)) moves its child node 2;
# node 3 rotates 90 degrees about z at t = 1 (STEP); node 4 scales 1 -> 3
# (CUBICSPLINE, zero tangents: smoothstep). Triangles in order: 0 static,
# 1, 2, 3 moving.
b = Builder()
pos = b.vec3(TRI)
t01 = b.add("f", [0, 1], "SCALAR", FLOAT, min=[0], max=[1])
t02 = b.add("f", [0, 2], "SCALAR", FLOAT, min=[0], max=[2])
moves = b.add("f", [0, 0, 0, 4, 0, 0], "VEC3", FLOAT)
turns = b.add("f", [0, 0, 0, 1, 0, 0, 0.7071067811865476, 0.7071067811865476], "VEC4", FLOAT)
# in-tangent, value, out-tangent per key
grows = b.add("f", [0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 3, 3, 3, 0, 0, 0], "VEC3", FLOAT)
write("animated.gltf", b.gltf(
    scenes=[{"nodes": [0, 1, 3, 4]}],
    nodes=[{"mesh": 0}, {"children": [2]}, {"mesh": 0}, {"mesh": 0}, {"mesh": 0}],
    meshes=[{"primitives": [{"attributes": {"POSITION": pos}}]}],
    animations=[{
        "samplers": [{"input": t02, "output": moves, "interpolation": "LINEAR"},
                     {"input": t01, "output": turns, "interpolation": "STEP"},
                     {"input": t02, "output": grows, "interpolation": "CUBICSPLINE"}],
        "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}},
                     {"sampler": 1, "target": {"node": 3, "path": "rotation"}},
                     {"sampler": 2, "target": {"node": 4, "path": "scale"}}]}]))

# morph.gltf: a unit quad (two triangles) with one morph target lifting every
# vertex by (0, 0, 1); its weight goes 0 -> 1 over t 0 -> 1 (LINEAR).
b = Builder()
quad = b.vec3([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 0, 0), (1, 1, 0), (0, 1, 0)])
lift = b.vec3([(0, 0, 1)] * 6)
keys = b.add("f", [0, 1], "SCALAR", FLOAT, min=[0], max=[1])
weights = b.add("f", [0, 1], "SCALAR", FLOAT)
write("morph.gltf", b.gltf(
    scenes=[{"nodes": [0]}], nodes=[{"mesh": 0}],
    meshes=[{"primitives": [{"attributes": {"POSITION": quad}, "targets": [{"POSITION": lift}]}], "weights": [0]}],
    animations=[{"samplers": [{"input": keys, "output": weights}],
                 "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]))

# dynamic.gltf: the built-in dynamic scene of --dynamic (tests/e2e/
# dynamic_cli_test.cpp): static geometry (a floor of 512 triangles, four
# pillars, a sphere) and three moving objects over t 0 -> 2, looped (the last
# key equals the first): a sphere on a rigid path (translation, LINEAR), a
# bar spinning about y (rotation, LINEAR) and a sphere morphing between
# three equally spaced keyframe meshes (two morph targets, weights LINEAR:
# base, stretched, squashed, base). 1,404 triangles, 652 of them moving.
import math


def grid(n, size):
    tris = []
    step = 2.0 * size / n
    for i in range(n):
        for j in range(n):
            x0, z0 = -size + i * step, -size + j * step
            a, b, c, d = (x0, 0, z0), (x0 + step, 0, z0), (x0 + step, 0, z0 + step), (x0, 0, z0 + step)
            tris += [a, c, b, a, d, c]
    return tris


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]
    tris = []
    for a, b, c, d in faces:
        tris += [v[a], v[b], v[c], v[a], v[c], v[d]]
    return tris


def sphere(radius, slices, stacks, scale=(1, 1, 1)):
    def point(i, j):
        theta, phi = math.pi * j / stacks, 2 * math.pi * i / slices
        return (radius * scale[0] * math.sin(theta) * math.cos(phi), radius * scale[1] * math.cos(theta),
                radius * scale[2] * math.sin(theta) * math.sin(phi))
    tris = []
    for i in range(slices):
        for j in range(stacks):
            a, b, c, d = point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)
            tris += [a, c, b, a, d, c]
    return tris


def delta(target, base):
    return [tuple(t[k] - b[k] for k in range(3)) for t, b in zip(target, base)]


def turn(degrees):  # quaternion about y
    h = math.radians(degrees) / 2
    return [0, math.sin(h), 0, math.cos(h)]


b = Builder()
floor = b.vec3(grid(16, 4.0))
pillars = b.vec3(box((-3.2, 0, -3.2), (-2.8, 2, -2.8)) + box((2.8, 0, -3.2), (3.2, 2, -2.8)) +
                 box((-3.2, 0, 2.8), (-2.8, 2, 3.2)) + box((2.8, 0, 2.8), (3.2, 2, 3.2)))
still = b.vec3(sphere(0.8, 16, 6))
ball = b.vec3(sphere(0.6, 16, 10))
bar = b.vec3(box((-1.5, -0.15, -0.15), (1.5, 0.15, 0.15)))
blob_base = sphere(0.7, 16, 10)
blob = b.vec3(blob_base)
stretched = b.vec3(delta(sphere(0.7, 16, 10, (0.6, 1.8, 0.6)), blob_base))
squashed = b.vec3(delta(sphere(0.7, 16, 10, (1.5, 0.5, 1.5)), blob_base))
keys5 = b.add("f", [0, 0.5, 1, 1.5, 2], "SCALAR", FLOAT, min=[0], max=[2])
path = b.add("f", [-2, 0.6, -1, 2, 0.6, -1, 2, 1.8, 1.5, -2, 0.6, 1.5, -2, 0.6, -1], "VEC3", FLOAT)
spin = b.add("f", turn(0) + turn(90) + turn(180) + turn(270) + turn(360), "VEC4", FLOAT)
keys4 = b.add("f", [0, 2 / 3, 4 / 3, 2], "SCALAR", FLOAT, min=[0], max=[2])
morphs = b.add("f", [0, 0, 1, 0, 0, 1, 0, 0], "SCALAR", FLOAT)
write("dynamic.gltf", b.gltf(
    scenes=[{"nodes": [0, 1, 2, 3, 4, 5, 6, 7]}],
    extensionsUsed=["KHR_lights_punctual"],
    extensions={"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1], "intensity": 30}]}},
    cameras=[{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1}}],
    nodes=[
        {"translation": [0, 5, 9], "rotation": [-0.25038, 0, 0, 0.96815], "camera": 0},
        {"translation": [3, 6, 4], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"mesh": 0},
        {"mesh": 1},
        {"translation": [0, 0.8, 0], "mesh": 2},
        {"translation": [-2, 0.6, -1], "mesh": 3},
        {"translation": [0, 2.6, 0], "mesh": 4},
        {"translation": [2, 1.2, -2.2], "mesh": 5, "weights": [0, 0]},
    ],
    materials=[
        {"pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.65, 1], "metallicFactor": 0.0}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1], "metallicFactor": 0.0}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 1.0, "roughnessFactor": 0.0}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 1], "metallicFactor": 0.0}},
    ],
    meshes=[{"primitives": [{"attributes": {"POSITION": floor}, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": pillars}, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": still}, "material": 2}]},
            {"primitives": [{"attributes": {"POSITION": ball}, "material": 1}]},
            {"primitives": [{"attributes": {"POSITION": bar}, "material": 3}]},
            {"primitives": [{"attributes": {"POSITION": blob},
                             "targets": [{"POSITION": stretched}, {"POSITION": squashed}], "material": 1}],
             "weights": [0, 0]}],
    animations=[{
        "samplers": [{"input": keys5, "output": path, "interpolation": "LINEAR"},
                     {"input": keys5, "output": spin, "interpolation": "LINEAR"},
                     {"input": keys4, "output": morphs, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": 5, "path": "translation"}},
                     {"sampler": 1, "target": {"node": 6, "path": "rotation"}},
                     {"sampler": 2, "target": {"node": 7, "path": "weights"}}]}]))
