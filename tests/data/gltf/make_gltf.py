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

# view.gltf: camera, KHR point light, mirror and diffuse materials, normals
# under a non-uniform scale.
b = Builder()
pos = b.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
nrm = b.vec3([(1, 1, 0), (1, 1, 0), (1, 1, 0)])
write("view.gltf", b.gltf(
    scenes=[{"nodes": [0, 1, 2, 3]}],
    extensionsUsed=["KHR_lights_punctual"],
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
        {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0.0, "roughnessFactor": 0.5}},
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
