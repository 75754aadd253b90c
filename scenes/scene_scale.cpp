#include "scenes/scene_scale.h"

#include <cmath>

namespace passtrace {

glm::vec3 scaleByPowerOfTwo(const glm::vec3& x, int k) {
  return {std::ldexp(x.x, k), std::ldexp(x.y, k), std::ldexp(x.z, k)};
}

int sceneScaleExponent(const Scene& scene) {
  float largest = 0.0f;
  for (const Triangle& t : scene.triangles)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2})
      largest = std::fmax(largest, std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z))));
  if (!(largest > 0.0f) || !std::isfinite(largest)) return 0;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest = f · 2^exponent, f in [0.5, 1)
  const int magnitude = exponent - 1;  // largest in [2^magnitude, 2^(magnitude+1))
  if (magnitude >= kMinSafeExponent && magnitude <= kMaxSafeExponent) return 0;
  return -magnitude;
}

int normalizeSceneScale(Scene& scene) {
  const int k = sceneScaleExponent(scene);
  if (k == 0) return 0;
  for (Triangle& t : scene.triangles) {
    t.v0 = scaleByPowerOfTwo(t.v0, k);
    t.v1 = scaleByPowerOfTwo(t.v1, k);
    t.v2 = scaleByPowerOfTwo(t.v2, k);
  }
  scene.camera.eye = scaleByPowerOfTwo(scene.camera.eye, k);
  scene.camera.lookAt = scaleByPowerOfTwo(scene.camera.lookAt, k);
  scene.light.position = scaleByPowerOfTwo(scene.light.position, k);
  for (PointLight& l : scene.lights) l.position = scaleByPowerOfTwo(l.position, k);
  scene.scaleExponent += k;
  return k;
}

}  // namespace passtrace
