#pragma once
// The formats passtrace does not read itself (STL, FBX, COLLADA, 3DS, X),
// read with the Open Asset Import Library (Assimp) and chosen by file
// extension (assimpExtensions). Errors are "FILE: reason", Assimp's own
// message as the reason. PLY and OFF are read by passtrace (ply_reader.h,
// off_reader.h): Assimp misreads some valid binary PLY bodies and clamps
// OFF's out-of-range indices.
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
// materials (STL), and for Assimp's invented "DefaultMaterial",
// Material{}, the OBJ loader's default. Normals: kept when a mesh has them,
// the geometric normal for the others. View and light are framed on the
// bounds as for OBJ (a file's cameras and lights are not read).

#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace passtrace {

// The lower-case extensions (".stl", ...) read through Assimp.
const std::vector<std::string>& assimpExtensions();

// The scene's name is the file's stem.
Scene loadWithAssimp(const std::filesystem::path& path);

}  // namespace passtrace
