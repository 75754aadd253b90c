#include "scenes/indexed_mesh.h"

#include <cmath>
#include <iostream>
#include <string>

#include "scenes/polygon_triangulation.h"
#include "scenes/scene_error.h"
#include "scenes/tessellate.h"

namespace passtrace {

Scene meshScene(const std::filesystem::path& file, const IndexedMesh& mesh) {
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (!finite(mesh.positions[v])) throw SceneError(file, "vertex " + std::to_string(v) + " is not finite");
  const bool withNormals = !mesh.normals.empty();
  if (withNormals && mesh.normals.size() != mesh.positions.size())
    throw SceneError(file, "normals and vertices differ in number");

  Scene scene;
  scene.name = file.stem().string();
  scene.materials.push_back(Material{});
  PolygonWarnings warnings;
  std::size_t skipped = 0;
  std::vector<glm::vec3> polygon;
  uint64_t begin = 0;
  for (const uint64_t end : mesh.polygonEnds) {
    if (end < begin || end > mesh.corners.size()) throw SceneError(file, "polygon corners out of order");
    const uint32_t* corners = mesh.corners.data() + begin;
    const auto count = static_cast<std::size_t>(end - begin);
    begin = end;
    if (count < 3) {
      ++skipped;
      continue;
    }
    polygon.clear();
    for (std::size_t k = 0; k < count; ++k) {
      if (corners[k] >= mesh.positions.size()) throw SceneError(file, "vertex index out of range");
      polygon.push_back(mesh.positions[corners[k]]);
    }
    const PolygonTriangles split = triangulatePolygon(polygon);
    warnings.count(split.shape);
    for (const auto& [a, b, c] : split.triangles) {
      const Triangle t{polygon[a], polygon[b], polygon[c]};
      scene.triangles.push_back(t);
      scene.materialIds.push_back(0);
      if (!withNormals) continue;
      const glm::vec3 geometric = faceNormal(t);
      std::array<glm::vec3, 3> normals{};
      const uint32_t ids[3] = {corners[a], corners[b], corners[c]};
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 n = mesh.normals[ids[k]];
        const float length = glm::length(n);
        normals[static_cast<std::size_t>(k)] = length > 0.0f && std::isfinite(length) ? n / length : geometric;
      }
      scene.vertexNormals.push_back(normals);
    }
  }
  if (scene.triangles.empty()) throw SceneError(file, "no triangles");
  if (skipped > 0)
    std::cerr << file.string() << ": skipped " << skipped << " point and line primitive" << (skipped == 1 ? "" : "s")
              << "\n";
  std::cerr << warnings.text(file);
  return scene;
}

}  // namespace passtrace
