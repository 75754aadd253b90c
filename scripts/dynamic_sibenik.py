"""Papay's dynamic Sibenik scenes (seed 003, Tables D.47-D.52): the static
cathedral (N_S = 75,284) with one, two or three moving objects (the seed's
N_D = 6,658 / 13,316 / 19,974). The seed does not say what its objects are;
here each is a sphere of 6,656 triangles (64 slices x 53 stacks, the nearest
closed lat-long sphere to 6,658) flying down the nave on a straight path,
one metre above the floor in its own lane, so the moving triangles cross
many leaves of the static tree as the seed's do.

The static part is passtrace's own --export of `-s sibenik` (same triangles,
same order), so the file holds exactly the copy the other reports use. The
view and light are Sibenik's standard ones, given on the command line
(VIEW_ARGS), since the export carries neither.
"""
import base64
import json
import math
import pathlib
import struct
import subprocess

import bench_ranks

OBJECT_TRIANGLES = 6656
SLICES, STACKS, RADIUS = 64, 53, 1.2
# In the exported file's units (metres): the nave runs along x, the floor is near y = -13.
LANES_Z = [0.0, -3.0, 3.0]
PATH_X = (-12.0, 12.0)
HEIGHT_Y = -10.5
VIEW_ARGS = ["--eye", "-17,-11,0", "--look-at", "5,-9,0", "--fov", "55", "--light", "-12,-4,0"]


def sphere_triangles():
    """Non-indexed positions of a lat-long sphere: 2 * SLICES * (STACKS - 1) triangles."""
    def point(i, j):
        theta, phi = math.pi * i / STACKS, 2 * math.pi * j / SLICES
        return (RADIUS * math.sin(theta) * math.cos(phi), RADIUS * math.cos(theta),
                RADIUS * math.sin(theta) * math.sin(phi))
    tris = []
    for i in range(STACKS):
        for j in range(SLICES):
            a, b, c, d = point(i, j), point(i, j + 1), point(i + 1, j), point(i + 1, j + 1)
            if i > 0:
                tris.append((a, d, b))
            if i < STACKS - 1:
                tris.append((a, c, d))
    assert len(tris) == OBJECT_TRIANGLES, len(tris)
    return tris


def add_buffer(doc, data):
    doc["buffers"].append({"byteLength": len(data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
    return len(doc["buffers"]) - 1


def add_accessor(doc, buffer, offset, length, count, kind, **extra):
    doc["bufferViews"].append({"buffer": buffer, "byteOffset": offset, "byteLength": length})
    doc["accessors"].append(dict({"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126, "count": count,
                                  "type": kind}, **extra))
    return len(doc["accessors"]) - 1


def make(binary, objects, out_dir):
    """Writes OUT_DIR/sibenikK.gltf (K = objects) and returns its path."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    static = out_dir / "sibenik_static.gltf"
    if not static.exists():
        subprocess.run([str(binary), "-s", "sibenik", "--export", str(static), "-q"], check=True,
                       capture_output=True, text=True, env=bench_ranks.child_env())
    doc = json.loads(static.read_text())
    tris = sphere_triangles()
    positions = [c for t in tris for p in t for c in p]
    lo = [min(positions[k::3]) for k in range(3)]
    hi = [max(positions[k::3]) for k in range(3)]
    times, keys = [0.0, 1.0], []
    for lane in LANES_Z[:objects]:
        keys += [PATH_X[0], HEIGHT_Y, lane, PATH_X[1], HEIGHT_Y, lane]
    data = struct.pack(f"<{len(positions)}f", *positions)
    time_offset = len(data)
    data += struct.pack("<2f", *times)
    key_offset = len(data)
    data += struct.pack(f"<{len(keys)}f", *keys)
    buffer = add_buffer(doc, data)
    mesh_positions = add_accessor(doc, buffer, 0, time_offset, len(positions) // 3, "VEC3", min=lo, max=hi)
    time_accessor = add_accessor(doc, buffer, time_offset, 8, 2, "SCALAR", min=[0.0], max=[1.0])
    doc["meshes"].append({"name": "mover", "primitives": [{"attributes": {"POSITION": mesh_positions}}]})
    mesh = len(doc["meshes"]) - 1
    samplers, channels = [], []
    for k in range(objects):
        doc["nodes"].append({"name": f"mover{k + 1}", "mesh": mesh, "translation": keys[6 * k:6 * k + 3]})
        node = len(doc["nodes"]) - 1
        doc["scenes"][doc.get("scene", 0)]["nodes"].append(node)
        out = add_accessor(doc, buffer, key_offset + 24 * k, 24, 2, "VEC3")
        samplers.append({"input": time_accessor, "output": out, "interpolation": "LINEAR"})
        channels.append({"sampler": k, "target": {"node": node, "path": "translation"}})
    doc["animations"] = [{"samplers": samplers, "channels": channels}]
    path = out_dir / f"sibenik{objects}.gltf"
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(json.dumps(doc))
    tmp.replace(path)
    return path
