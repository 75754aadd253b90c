#include "render/shading.h"

namespace passtrace {

float secondaryRayEpsilon(const Scene& scene) {
  const Aabb box = scene.bounds();
  return box.empty() ? 1e-4f : 1e-4f * glm::length(box.extent());
}

namespace {

// A nearest hit as shading sees it: its material, the shading normal n and
// the geometric normal ng both facing the incoming ray (triangles are
// two-sided), and where rays leaving it start.
struct SurfacePoint {
  const Material* material;
  glm::vec3 n, ng, origin;
};

SurfacePoint surfaceAt(const Scene& scene, float epsilon, const Ray& ray, const Hit& hit,
                       std::span<const ShadingEntry> table) {
  const ShadingEntry entry = table.empty()
      ? ShadingEntry{glm::normalize(scene.triangles[hit.id].geometricNormal()), scene.materialIds[hit.id]}
      : table[hit.id];
  const glm::vec3 d = ray.direction;
  const glm::vec3 position = ray.origin + hit.t * d;
  glm::vec3 geometric = entry.normal;
  glm::vec3 n = geometric;
  if (scene.hasVertexNormals()) {
    const auto& vn = scene.vertexNormals[hit.id];
    n = glm::normalize(vn[0] * (1.0f - hit.u - hit.v) + vn[1] * hit.u + vn[2] * hit.v);
  }
  const glm::vec3 ng = glm::dot(geometric, d) > 0.0f ? -geometric : geometric;
  if (glm::dot(n, ng) < 0.0f) n = -n;
  return SurfacePoint{&scene.materials[entry.material], n, ng, position + epsilon * ng};
}

// The point light seen from a surface point: the unit direction to it, its
// distance, and N.L (0 where the light is behind the geometric normal).
struct LightDirection {
  glm::vec3 l;
  float distance, nDotL;
};

LightDirection towardLight(const Scene& scene, const SurfacePoint& s) {
  const glm::vec3 toLight = scene.light.position - s.origin;
  const float distance = glm::length(toLight);
  const glm::vec3 l = toLight / distance;
  const float nDotL = glm::dot(s.ng, l) > 0.0f ? std::max(glm::dot(s.n, l), 0.0f) : 0.0f;
  return LightDirection{l, distance, nDotL};
}

}  // namespace

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
  const SurfacePoint s = surfaceAt(scene, epsilon, path.ray, hit, table);
  const Material& material = *s.material;
  if (material.isMirror()) {
    if (!lastBounce) {
      path.kind = RayKind::Nearest;
      path.ray = Ray{s.origin, glm::reflect(path.ray.direction, s.n), kInfinity};
      path.throughput *= material.mirror;
    }
    return;
  }
  path.color += path.throughput * scene.ambient * material.diffuse;
  const LightDirection light = towardLight(scene, s);
  const glm::vec3 direct = path.throughput * material.diffuse * scene.light.color * light.nDotL;
  if (lastBounce) {
    path.color += direct;
  } else if (light.nDotL > 0.0f) {
    path.kind = RayKind::Shadow;
    path.ray = Ray{s.origin, light.l, light.distance};
    path.pending = direct;
  }
}

// shadeElement's arithmetic with the fresh path's colour 0 and throughput 1
// folded in (x * 1 and 0 + x are exact), so the colours are the same bits.
glm::vec3 shadePrimaryOnly(const Scene& scene, float epsilon, const Ray& ray, const Hit& hit,
                           std::span<const ShadingEntry> table) {
  if (!(hit.t < ray.tMax)) return scene.background;
  const SurfacePoint s = surfaceAt(scene, epsilon, ray, hit, table);
  const Material& material = *s.material;
  if (material.isMirror()) return glm::vec3(0.0f);
  const glm::vec3 ambient = scene.ambient * material.diffuse;
  return ambient + material.diffuse * scene.light.color * towardLight(scene, s).nDotL;
}

}  // namespace passtrace
