#include "accel/brute_force.h"

namespace passtrace {

Hit intersectBruteForce(std::span<const Triangle> tris, const Ray& ray, bool anyHit, RayStats* stats, TriangleTest test) {
  Hit best{ray.tMax};
  uint32_t tested = 0;
  for (size_t i = 0; i < tris.size(); ++i) {
    ++tested;
    intersectTriangle(ray.origin, ray.direction, tris[i], static_cast<uint32_t>(i), best, test);
    if (anyHit && best.found()) break;
  }
  if (stats) {
    stats->steps += tested;
    stats->triangleTests += tested;
  }
  return best;
}

}  // namespace passtrace
