// --shading whitted on the CPU; kernels_glsl/shade_whitted.frag is the same
// computation in the same order (the two images are compared in tests).
#include <algorithm>
#include <cmath>

#include "render/shading.h"

namespace passtrace {
namespace {

void push(WhittedStack& stack, const Ray& ray, glm::vec3 throughput, int depth) {
  if (std::max({throughput.r, throughput.g, throughput.b}) < kWhittedMinThroughput) return;
  if (stack.count == kWhittedStackSize) return;  // full: the new ray is dropped
  stack.entries[size_t(stack.count++)] = PendingRay{ray, throughput, depth, RayKind::Nearest};
}

void pushShadow(WhittedStack& stack, const Ray& ray, glm::vec3 light) {
  if (stack.count == kWhittedStackSize) return;
  stack.entries[size_t(stack.count++)] = PendingRay{ray, light, 0, RayKind::Shadow};
}

// Schlick's approximation of the dielectric Fresnel reflectance; for a ray
// leaving the denser medium the cosine of the transmitted angle is used, so
// the curve is the same from both sides.
float schlick(float ior, float cosine) {
  const float r0 = ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
  const float c = 1.0f - cosine;
  return r0 + (1.0f - r0) * (c * c * c * c * c);
}

}  // namespace

int whittedLightCount(const Scene& scene) {
  return scene.lights.empty() ? 1 : std::min(int(scene.lights.size()), kWhittedMaxLights);
}

const PointLight& whittedLight(const Scene& scene, int k) {
  return scene.lights.empty() ? scene.light : scene.lights[size_t(k)];
}

void shadeWhitted(const Scene& scene, float epsilon, int maxDepth, const Hit& hit, PathState& path,
                  WhittedStack& stack, std::span<const ShadingEntry> table) {
  const RayKind kind = path.kind;
  path.kind = RayKind::None;
  const bool found = hit.t < path.ray.tMax;
  if (kind == RayKind::Shadow) {
    if (!found) path.color += path.pending;
  } else if (kind == RayKind::Nearest && !found) {
    path.color += path.throughput * scene.background;
  } else if (kind == RayKind::Nearest) {
    const ShadingEntry entry = table.empty()
        ? ShadingEntry{glm::normalize(scene.triangles[hit.id].geometricNormal()), scene.materialIds[hit.id]}
        : table[hit.id];
    const Material& m = scene.materials[entry.material];
    const glm::vec3 d = path.ray.direction;
    const glm::vec3 position = path.ray.origin + hit.t * d;
    const glm::vec3 geometric = entry.normal;
    glm::vec3 n = geometric;
    if (scene.hasVertexNormals()) {
      const auto& vn = scene.vertexNormals[hit.id];
      n = glm::normalize(vn[0] * (1.0f - hit.u - hit.v) + vn[1] * hit.u + vn[2] * hit.v);
    }
    // The ray enters a closed transmissive mesh where it meets the front side.
    const bool entering = glm::dot(geometric, d) <= 0.0f;
    const glm::vec3 ng = entering ? geometric : -geometric;
    if (glm::dot(n, ng) < 0.0f) n = -n;
    const glm::vec3 front = position + epsilon * ng, back = position - epsilon * ng;
    const glm::vec3 thr = path.throughput;
    const bool mirror = m.isMirror();
    const float t = mirror ? 0.0f : m.transmission;
    if (!mirror) path.color += thr * scene.ambient * m.diffuse * (1.0f - t);

    if (path.depth < maxDepth) {
      const int depth = path.depth + 1;
      if (mirror) {
        push(stack, Ray{front, glm::reflect(d, n), kInfinity}, thr * m.mirror, depth);
      } else if (t > 0.0f) {
        const float eta = entering ? 1.0f / m.ior : m.ior;
        const float cosi = std::clamp(-glm::dot(d, n), 0.0f, 1.0f);
        const float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
        float fresnel = 1.0f;  // total internal reflection when k < 0
        if (k >= 0.0f) {
          const float cost = std::sqrt(k);
          fresnel = schlick(m.ior, eta > 1.0f ? cost : cosi);
          const glm::vec3 refracted = eta * d + (eta * cosi - cost) * n;
          push(stack, Ray{back, refracted, kInfinity}, thr * (t * (1.0f - fresnel)), depth);
        }
        push(stack, Ray{front, glm::reflect(d, n), kInfinity}, thr * (t * fresnel), depth);
      }
    }

    if (!mirror) {
      const int lights = whittedLightCount(scene);
      for (int k = lights - 1; k >= 0; --k) {  // the first light's ray ends up traced next
        const PointLight& light = whittedLight(scene, k);
        const glm::vec3 toLight = light.position - front;
        const float distance = glm::length(toLight);
        const glm::vec3 l = toLight / distance;
        const float nDotL = glm::dot(ng, l) > 0.0f ? std::max(glm::dot(n, l), 0.0f) : 0.0f;
        if (nDotL <= 0.0f) continue;
        float highlight = 0.0f;
        if (m.specular.r > 0.0f || m.specular.g > 0.0f || m.specular.b > 0.0f)
          highlight = std::pow(std::max(glm::dot(glm::reflect(-l, n), -d), 0.0f), m.shininess);
        const glm::vec3 direct = thr * light.color * (m.diffuse * (nDotL * (1.0f - t)) + m.specular * highlight);
        if (!(direct.r > 0.0f || direct.g > 0.0f || direct.b > 0.0f)) continue;
        if (path.kind == RayKind::Shadow) pushShadow(stack, path.ray, path.pending);  // a later light's
        path.kind = RayKind::Shadow;
        path.ray = Ray{front, l, distance};
        path.pending = direct;
      }
    }
  }
  if (path.kind == RayKind::None && stack.count > 0) {
    const PendingRay& next = stack.entries[size_t(--stack.count)];
    path.kind = next.kind;
    path.ray = next.ray;
    if (next.kind == RayKind::Shadow) {
      path.pending = next.throughput;
    } else {
      path.throughput = next.throughput;
      path.depth = next.depth;
    }
  }
}

}  // namespace passtrace
