#include "render/scene_streams.h"

#include "stream/texel_address.h"

namespace passtrace {

std::vector<glm::vec4> triangleShadingTexels(const Scene& scene) {
  std::vector<glm::vec4> texels;
  texels.reserve(4 * scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const glm::vec3 geometric = glm::normalize(scene.triangles[i].geometricNormal());
    const std::array<glm::vec3, 3> n =
        scene.hasVertexNormals() ? scene.vertexNormals[i] : std::array<glm::vec3, 3>{geometric, geometric, geometric};
    texels.emplace_back(n[0], packIndex(scene.materialIds[i]));
    texels.emplace_back(n[1], 0.0f);
    texels.emplace_back(n[2], 0.0f);
    texels.emplace_back(geometric, 0.0f);
  }
  return texels;
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
