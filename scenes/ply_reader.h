#pragma once
// passtrace's own PLY reader: the header by ply_header.h, the body here, in
// all three formats (ascii, binary_little_endian, binary_big_endian), every
// scalar type under either name, list counts of any integer type.
//
// Why not Assimp: Assimp 5.2's PLY reader skips whitespace after end_header
// before a binary body, so a body whose first byte is 0x0A, 0x0D, 0x20 or
// 0x09 (a first x coordinate whose low byte is 10, as in scans written by
// MeshLab's VCGLIB) is read one byte off and the file fails ("aiMesh::mFaces
// [4]::mIndices[0] is out of range"): Assimp issue #5341, open. A reader of
// our own also names out-of-range indices and truncation precisely.
//
// What is read: element "vertex" (x, y, z of any type; nx, ny, nz when all
// three are there), elements "face" (a list "vertex_indices" or
// "vertex_index": polygons) and "tristrips" (the same list: strips, -1
// restarting one; triangle k of a strip is (k, k+1, k+2), every other one
// flipped to keep the winding). Every other property and element (Stanford's
// confidence and intensity, range_grid, edge, material, ...) is skipped,
// lists included. Elements may come in any order. ASCII instances are one
// per line holding exactly their values (blank lines between them are
// skipped, text after the last one is an error); binary bytes after the last
// element are ignored (writers pad). Errors: "FILE:LINE: reason" in ASCII,
// "FILE: reason" in binary: a face naming a vertex out of range, a truncated
// body, a number that is not one or does not fit its type, a vertex that is
// not finite. The scene then follows indexed_mesh.h (file order, one
// material, normals where given); the registry frames it.

#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

Scene loadPly(const std::filesystem::path& path);

}  // namespace passtrace
