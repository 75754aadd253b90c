#include "render/shading.h"

namespace passtrace {

float secondaryRayEpsilon(const Scene& scene) {
  const Aabb box = scene.bounds();
  return box.empty() ? 1e-4f : 1e-4f * glm::length(box.extent());
}

void shadeElement(const Scene& scene, float epsilon, bool lastBounce, const Hit& hit, PathState& path,
                  std::span<const ShadingEntry> table) {
  const RayKind kind = path.kind;
  path.kind = RayKind::None;
  const bool found = hit.t < path.ray.tMax;
  if (kind == RayKind::Shadow) {
    if (!found) path.color += path.pending;
    return;
  }
  if (kind != RayKind::Nearest) return;
  if (!found) {
    path.color += path.throughput * scene.background;
    return;
  }
  const ShadingEntry entry = table.empty()
      ? ShadingEntry{glm::normalize(scene.triangles[hit.id].geometricNormal()), scene.materialIds[hit.id]}
      : table[hit.id];
  const Material& material = scene.materials[entry.material];
  const glm::vec3 d = path.ray.direction;
  const glm::vec3 position = path.ray.origin + hit.t * d;
  glm::vec3 geometric = entry.normal;
  glm::vec3 n = geometric;
  if (scene.hasVertexNormals()) {
    const auto& vn = scene.vertexNormals[hit.id];
    n = glm::normalize(vn[0] * (1.0f - hit.u - hit.v) + vn[1] * hit.u + vn[2] * hit.v);
  }
  // Both normals face the incoming ray: triangles are two-sided.
  const glm::vec3 ng = glm::dot(geometric, d) > 0.0f ? -geometric : geometric;
  if (glm::dot(n, ng) < 0.0f) n = -n;
  const glm::vec3 origin = position + epsilon * ng;

  if (material.isMirror()) {
    if (!lastBounce) {
      path.kind = RayKind::Nearest;
      path.ray = Ray{origin, glm::reflect(d, n), kInfinity};
      path.throughput *= material.mirror;
    }
    return;
  }
  path.color += path.throughput * scene.ambient * material.diffuse;
  const glm::vec3 toLight = scene.light.position - origin;
  const float distance = glm::length(toLight);
  const glm::vec3 l = toLight / distance;
  const float nDotL = glm::dot(ng, l) > 0.0f ? std::max(glm::dot(n, l), 0.0f) : 0.0f;
  const glm::vec3 direct = path.throughput * material.diffuse * scene.light.color * nDotL;
  if (lastBounce) {
    path.color += direct;
  } else if (nDotL > 0.0f) {
    path.kind = RayKind::Shadow;
    path.ray = Ray{origin, l, distance};
    path.pending = direct;
  }
}

}  // namespace passtrace
