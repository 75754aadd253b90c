#pragma once
// The formats passtrace does not read itself (PLY, STL, FBX, COLLADA, 3DS,
// ...), read with the Open Asset Import Library (Assimp) and chosen by file
// extension (assimpExtensions). Errors are "FILE: reason", Assimp's own
// message as the reason; a PLY file's header is checked first
// (ply_header.h: "FILE:LINE: reason"), so that element counts the file cannot
// hold never reach Assimp's allocations.
//
// Geometry: Assimp triangulates polygons (aiProcess_Triangulate: a convex
// quad becomes (0 1 2), (0 2 3) as in the OBJ loader; larger polygons by ear
// clipping), and this loader walks the node tree itself, depth first in child
// order, each node's meshes in its list order, each mesh's faces in file
// order, with the node's world transform (normals by the inverse transpose,
// winding reversed where the determinant is negative). Walking it here rather
// than with aiProcess_PreTransformVertices keeps that order: that step merges
// meshes by material. Assimp may start a triangle at another of its corners
// than the file does (same winding), so a triangle's corners can be a
// rotation of the file's. Points and lines are skipped with one warning line
// on stderr; a file without triangles is an error. Faces with more than 1024
// corners are refused (ear clipping is quadratic in them). Vertices that are
// not finite, before or after the transforms, are an error (scene.h's rule);
// zero-area triangles are kept.
//
// Materials: each Assimp material's diffuse colour; in formats without
// materials (PLY, STL, OFF), and for Assimp's invented "DefaultMaterial",
// Material{}, the OBJ loader's default. Normals: kept when a mesh has them,
// the geometric normal for the others. View and light are framed on the
// bounds as for OBJ (a file's cameras and lights are not read).

#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace passtrace {

// The lower-case extensions (".ply", ...) read through Assimp.
const std::vector<std::string>& assimpExtensions();

// The scene's name is the file's stem.
Scene loadWithAssimp(const std::filesystem::path& path);

}  // namespace passtrace
