#pragma once
// The scene of an indexed polygon mesh, the shape of PLY and OFF files:
// positions (and optionally one normal per position) and polygons naming
// them. The readers (ply_reader.h, off_reader.h) check every index where
// they can name the line; this turns the mesh into triangles.
//
// Triangles come in file order: each polygon in turn, split by
// polygon_triangulation.h's rule (a convex polygon as the fan (0, i, i + 1),
// as the OBJ loader does). Polygons of one or two corners (points, lines)
// are skipped with one counted warning line on stderr; a mesh left without
// triangles is an error. Vertices that are not finite are an error (scene.h's
// rule). One material, Material{}; the vertex normals where the file has
// them (normalised; the geometric normal where one is zero or not finite).
// The camera and light are left to the caller (the registry frames it).

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace passtrace {

struct IndexedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty, or one per position
  std::vector<uint32_t> corners;   // every polygon's vertex indices, in file order
  std::vector<uint64_t> polygonEnds;  // polygon p is corners[end(p - 1) .. end(p))
};

// Throws SceneError("FILE: reason"). The scene's name is the file's stem.
Scene meshScene(const std::filesystem::path& file, const IndexedMesh& mesh);

}  // namespace passtrace
