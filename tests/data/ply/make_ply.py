#!/usr/bin/env python3
"""Writes the small PLY files of tests/unit/ply_loader_test.cpp, and the
pyramid in the other formats read through Assimp (run from this directory;
the outputs are committed, so this is documentation). The COLLADA, 3DS, X and
ASCII FBX copies are Assimp's own exports (`assimp export`, Debian's
assimp-utils): Assimp 5.2 cannot re-read its own binary FBX export."""
import math, struct, subprocess

# A unit cube: six quads, counter-clockwise seen from outside (12 triangles).
CUBE_VERTICES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                 (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]

# A square pyramid on the cube's top: one quad and four triangles (6 triangles),
# so a file mixes face sizes.
PYRAMID_VERTICES = [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1), (0.5, 1, 0.5)]
PYRAMID_FACES = [(0, 1, 2, 3), (0, 4, 1), (1, 4, 2), (2, 4, 3), (3, 4, 0)]


def ascii_ply(vertices, faces, vertex_count=None, face_count=None):
    lines = ["ply", "format ascii 1.0", "comment passtrace test data",
             "element vertex %d" % (len(vertices) if vertex_count is None else vertex_count),
             "property float x", "property float y", "property float z",
             "element face %d" % (len(faces) if face_count is None else face_count),
             "property list uchar int vertex_indices", "end_header"]
    lines += [" ".join(str(c) for c in v) for v in vertices]
    lines += [" ".join(str(i) for i in (len(f),) + tuple(f)) for f in faces]
    return "\n".join(lines) + "\n"


def bunny_layout_ply(vertices, faces):
    """Binary little-endian in the Stanford bunny's layout (bun_zipper.ply):
    x y z confidence intensity as floats, faces as uchar count + int indices."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment zipper output\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property float confidence\nproperty float intensity\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(vertices), len(faces)))
    body = b"".join(struct.pack("<5f", *v, 1.0, 0.5) for v in vertices)
    body += b"".join(struct.pack("<B%di" % len(f), len(f), *f) for f in faces)
    return header.encode() + body


def write(name, data):
    with open(name, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def obj(vertices, faces):
    lines = ["v %s" % " ".join(str(c) for c in v) for v in vertices]
    lines += ["f %s" % " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


write("cube.ply", ascii_ply(CUBE_VERTICES, CUBE_QUADS))
write("cube.obj", obj(CUBE_VERTICES, CUBE_QUADS))  # the same mesh, for the OBJ-PLY comparison
write("pyramid_binary.ply", bunny_layout_ply(PYRAMID_VERTICES, PYRAMID_FACES))
write("pyramid.obj", obj(PYRAMID_VERTICES, PYRAMID_FACES))

# The pyramid as a binary STL (its quad split as Assimp splits it) and as OFF.
PYRAMID_TRIANGLES = [(0, 1, 2), (0, 2, 3)] + PYRAMID_FACES[1:]
stl = b"passtrace test data".ljust(80, b" ") + struct.pack("<I", len(PYRAMID_TRIANGLES))
for tri in PYRAMID_TRIANGLES:
    stl += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *PYRAMID_VERTICES[i]) for i in tri) + b"\0\0"
write("pyramid.stl", stl)
write("pyramid.off", "OFF\n%d %d 0\n" % (len(PYRAMID_VERTICES), len(PYRAMID_FACES)) +
      "".join("%s\n" % " ".join(str(c) for c in v) for v in PYRAMID_VERTICES) +
      "".join("%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in PYRAMID_FACES))
for fmt, ext in [("collada", "dae"), ("3ds", "3ds"), ("x", "x"), ("fbxa", "fbx")]:
    subprocess.run(["assimp", "export", "pyramid.obj", "pyramid." + ext, "-f" + fmt], check=True,
                   stdout=subprocess.DEVNULL)

# --- malformed ---------------------------------------------------------------
good = bunny_layout_ply(PYRAMID_VERTICES, PYRAMID_FACES)
write("truncated_binary.ply", good[: len(good) - 10])
write("index_out_of_range.ply", ascii_ply(PYRAMID_VERTICES, [(0, 1, 2), (0, 1, 99)]))
write("count_too_large.ply", ascii_ply(PYRAMID_VERTICES, PYRAMID_FACES, vertex_count=4000000000))
write("nan_vertex.ply", ascii_ply([(0, 0, 0), (float("nan"), 0, 0), (0, 1, 0)], [(0, 1, 2)]))
inf = bunny_layout_ply([(0, 0, 0), (math.inf, 0, 0), (0, 1, 0)], [(0, 1, 2)])
write("inf_vertex_binary.ply", inf)
write("garbage.ply", "ply\nthis is not a header\n\x01\x02\x03\n")
write("not_ply.ply", "solid cube\nendsolid cube\n")
write("points_only.ply", ascii_ply(PYRAMID_VERTICES, []))
write("bad_type.ply", ascii_ply(PYRAMID_VERTICES, PYRAMID_FACES).replace("property float y", "property real y"))
# Assimp sizes a list from its length before reading the items.
write("ascii_list_too_long.ply",
      ascii_ply([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)]).replace("\n3 0 1 2\n", "\n4000000000 0 1 2\n"))

# --- out-of-range vertex indices in the formats read through Assimp ----------
# Each the pyramid with its last face's first index out of range. Assimp 5.2
# rejects the COLLADA one itself; it clamps the 3DS and OFF ones, drops the
# X one from its face and the FBX mesh whole (scenes/assimp_index_watch.h).
write("index_out_of_range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
with open("pyramid.dae") as f:
    write("index_out_of_range.dae", f.read().replace("12 13 14 15 </p>", "12 13 14 99 </p>"))
with open("pyramid.x") as f:
    write("index_out_of_range.x", f.read().replace("3;15,14,13;;", "3;99,14,13;;"))
with open("pyramid.fbx") as f:
    write("index_out_of_range.fbx", f.read().replace("13,14,-16", "13,14,-100"))


def patch_3ds_last_face(data):
    """The first index of the last face in the first face list (chunk 0x4120)."""
    data = bytearray(data)
    def walk(at, end):
        while at + 6 <= end:
            chunk, length = struct.unpack_from("<HI", data, at)
            if chunk in (0x4D4D, 0x3D3D, 0x4100):
                walk(at + 6, at + length)
            elif chunk == 0x4000:  # an object: a name, then chunks
                walk(data.index(0, at + 6) + 1, at + length)
            elif chunk == 0x4120:
                count = struct.unpack_from("<H", data, at + 6)[0]
                struct.pack_into("<H", data, at + 8 + 8 * (count - 1), 99)
            at += length
    walk(0, len(data))
    return bytes(data)


with open("pyramid.3ds", "rb") as f:
    write("index_out_of_range.3ds", patch_3ds_last_face(f.read()))
