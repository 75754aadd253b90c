// --shading ao on the CPU; kernels_glsl/shade_ao.frag is the same computation.
#include "render/ao_sampling.h"
#include "render/shading.h"

namespace passtrace {

float aoDistance(const Scene& scene, const ShadingConfig& config) {
  if (config.aoDistance > 0.0f) return config.aoDistance;
  const Aabb box = scene.bounds();
  const float diagonal = box.empty() ? 1.0f : glm::length(box.extent());
  return diagonal > 0.0f ? kAoDistanceFraction * diagonal : 1.0f;
}

void shadeAo(const Scene& scene, float epsilon, int samples, float distance, uint32_t pixel, const Hit& hit,
             PathState& path, std::span<const ShadingEntry> table) {
  const RayKind kind = path.kind;
  path.kind = RayKind::None;
  const bool found = hit.t < path.ray.tMax;
  glm::vec3 origin = path.ray.origin;
  if (kind == RayKind::Nearest) {
    if (!found) {
      path.color += scene.background;
      return;
    }
    const glm::vec3 d = path.ray.direction;
    const glm::vec3 geometric =
        table.empty() ? glm::normalize(scene.triangles[hit.id].geometricNormal()) : table[hit.id].normal;
    path.aoNormal = glm::dot(geometric, d) > 0.0f ? -geometric : geometric;
    origin = path.ray.origin + hit.t * d + epsilon * path.aoNormal;
    path.sample = 0;
  } else if (kind == RayKind::Shadow) {
    if (!found) path.color += glm::vec3(1.0f / float(samples));
    if (++path.sample >= samples) return;
  } else {
    return;
  }
  path.kind = RayKind::Shadow;
  path.ray = Ray{origin, aoDirection(path.aoNormal, aoRandom(pixel, uint32_t(path.sample))), distance};
}

}  // namespace passtrace
