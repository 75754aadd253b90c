#include "render/scene_streams.h"

#include <algorithm>
#include <array>
#include <span>

#include "stream/texel_address.h"

namespace passtrace {
namespace {

constexpr size_t kShadingTexelsPerTriangle = 4;

// Triangles [first, first + count)'s texels into `out`.
void writeTriangleShadingTexels(const Scene& scene, size_t first, size_t count, glm::vec4* out) {
  for (size_t i = first; i < first + count; ++i) {
    const glm::vec3 geometric = glm::normalize(scene.triangles[i].geometricNormal());
    const std::array<glm::vec3, 3> n =
        scene.hasVertexNormals() ? scene.vertexNormals[i] : std::array<glm::vec3, 3>{geometric, geometric, geometric};
    *out++ = glm::vec4(n[0], packIndex(scene.materialIds[i]));
    *out++ = glm::vec4(n[1], 0.0f);
    *out++ = glm::vec4(n[2], 0.0f);
    *out++ = glm::vec4(geometric, 0.0f);
  }
}

}  // namespace

std::vector<glm::vec4> triangleShadingTexels(const Scene& scene) {
  std::vector<glm::vec4> texels(kShadingTexelsPerTriangle * scene.triangles.size());
  writeTriangleShadingTexels(scene, 0, scene.triangles.size(), texels.data());
  return texels;
}

std::unique_ptr<ConstInputStream> triangleShadingStream(const Scene& scene, uint64_t maxPageTexels) {
  constexpr size_t kPiece = size_t(1) << 16;  // triangles
  auto stream = std::make_unique<ConstInputStream>(kShadingTexelsPerTriangle * scene.triangles.size(),
                                                   "triangle shading data", maxPageTexels);
  std::vector<glm::vec4> piece(kShadingTexelsPerTriangle * kPiece);
  for (size_t first = 0; first < scene.triangles.size(); first += kPiece) {
    const size_t count = std::min(kPiece, scene.triangles.size() - first);
    writeTriangleShadingTexels(scene, first, count, piece.data());
    stream->write(kShadingTexelsPerTriangle * first,
                  std::span<const glm::vec4>(piece.data(), kShadingTexelsPerTriangle * count));
  }
  return stream;
}

std::vector<glm::vec4> materialTexels(const Scene& scene) {
  std::vector<glm::vec4> texels;
  for (const Material& m : scene.materials) {
    texels.emplace_back(m.diffuse, 0.0f);
    texels.emplace_back(m.mirror, 0.0f);
  }
  return texels;
}

std::vector<glm::vec4> whittedMaterialTexels(const Scene& scene) {
  std::vector<glm::vec4> texels;
  for (const Material& m : scene.materials) {
    texels.emplace_back(m.diffuse, 0.0f);
    texels.emplace_back(m.mirror, 0.0f);
    texels.emplace_back(m.specular, m.shininess);
    texels.emplace_back(m.transmission, m.ior, 0.0f, 0.0f);
  }
  return texels;
}

}  // namespace passtrace
