#include "render/scene_streams.h"

#include <algorithm>
#include <array>
#include <span>

#include "stream/texel_address.h"

namespace passtrace {
namespace {

// Triangles [first, first + count)'s texels into `out`.
void writeTriangleShadingTexels(const Scene& scene, size_t first, size_t count, glm::vec4* out) {
  const bool flat = !scene.hasVertexNormals();
  for (size_t i = first; i < first + count; ++i) {
    const glm::vec3 geometric = glm::normalize(scene.triangles[i].geometricNormal());
    const float material = packIndex(scene.materialIds[i]);
    if (flat) {
      *out++ = glm::vec4(geometric, material);
      continue;
    }
    const std::array<glm::vec3, 3>& n = scene.vertexNormals[i];
    *out++ = glm::vec4(n[0], material);
    *out++ = glm::vec4(n[1], 0.0f);
    *out++ = glm::vec4(n[2], 0.0f);
    *out++ = glm::vec4(geometric, 0.0f);
  }
}

}  // namespace

uint32_t shadingTexelsPerTriangle(const Scene& scene) { return scene.hasVertexNormals() ? 4 : 1; }

std::string shadingTexelsDefine(const Scene& scene) {
  return "SHADING_TEXELS " + std::to_string(shadingTexelsPerTriangle(scene));
}

std::vector<glm::vec4> triangleShadingTexels(const Scene& scene) {
  std::vector<glm::vec4> texels(shadingTexelsPerTriangle(scene) * scene.triangles.size());
  writeTriangleShadingTexels(scene, 0, scene.triangles.size(), texels.data());
  return texels;
}

std::unique_ptr<ConstInputStream> triangleShadingStream(const Scene& scene, uint64_t maxPageTexels) {
  constexpr size_t kPiece = size_t(1) << 16;  // triangles
  const size_t perTriangle = shadingTexelsPerTriangle(scene);
  auto stream = std::make_unique<ConstInputStream>(perTriangle * scene.triangles.size(), "triangle shading data",
                                                   maxPageTexels);
  std::vector<glm::vec4> piece(perTriangle * kPiece);
  for (size_t first = 0; first < scene.triangles.size(); first += kPiece) {
    const size_t count = std::min(kPiece, scene.triangles.size() - first);
    writeTriangleShadingTexels(scene, first, count, piece.data());
    stream->write(perTriangle * first, std::span<const glm::vec4>(piece.data(), perTriangle * count));
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
