#include "accel/octree/octree_revelles.h"

#include <algorithm>
#include <cmath>

namespace passtrace {

namespace {
// Revelles' table: the next child leaving `current` through axis k's exit plane.
constexpr int kNext[8][3] = {{1, 2, 4}, {8, 3, 5}, {3, 8, 6}, {8, 8, 7},
                             {5, 6, 8}, {8, 7, 8}, {7, 8, 8}, {8, 8, 8}};
}  // namespace

RevellesRay revellesStart(const Aabb& root, const glm::vec3& origin, const glm::vec3& direction) {
  RevellesRay r;
  glm::vec3 o = origin, d = direction;
  for (int k = 0; k < 3; ++k) {
    // A ray parallel to an axis (as safeInverse sees it) is mirrored when it
    // lies in the upper half, so it never sits on the root's exit face: one
    // lying in the root's max face would get t1 = 0 and leave at once.
    const bool parallel = std::fabs(d[k]) < 1e-20f;
    const float twice = root.min[k] + root.max[k];
    if (parallel ? o[k] + o[k] > twice : d[k] < 0.0f) {
      o[k] = twice - o[k];
      r.a |= 1 << k;
    }
    d[k] = std::fabs(d[k]);
  }
  const glm::vec3 inv = safeInverse(d);
  r.t0 = glm::clamp((root.min - o) * inv, glm::vec3(-kRevellesLimit), glm::vec3(kRevellesLimit));
  r.t1 = glm::clamp((root.max - o) * inv, glm::vec3(-kRevellesLimit), glm::vec3(kRevellesLimit));
  return r;
}

int revellesFirstChild(const glm::vec3& t0, const glm::vec3& tm) {
  int entry = 0;
  if (t0.y > t0[entry]) entry = 1;
  if (t0.z > t0[entry]) entry = 2;
  int child = 0;
  for (int k = 0; k < 3; ++k)
    if (k != entry && tm[k] < t0[entry]) child |= 1 << k;
  return child;
}

int revellesNextChild(int current, const glm::vec3& t1) {
  int exit = 0;
  if (t1.y < t1[exit]) exit = 1;
  if (t1.z < t1[exit]) exit = 2;
  return kNext[current][exit];
}

void revellesChild(int octant, const glm::vec3& t0, const glm::vec3& t1, const glm::vec3& tm, glm::vec3& c0,
                   glm::vec3& c1) {
  for (int k = 0; k < 3; ++k) {
    const bool upper = (octant >> k) & 1;
    c0[k] = upper ? tm[k] : t0[k];
    c1[k] = upper ? t1[k] : tm[k];
  }
}

std::vector<int> revellesChildOrder(const Aabb& box, const Ray& ray) {
  const RevellesRay r = revellesStart(box, ray.origin, ray.direction);
  std::vector<int> order;
  const float entry = std::max({r.t0.x, r.t0.y, r.t0.z}), exit = std::min({r.t1.x, r.t1.y, r.t1.z});
  if (entry > exit) return order;
  const glm::vec3 tm = 0.5f * (r.t0 + r.t1);
  for (int c = revellesFirstChild(r.t0, tm); c != kRevellesExit;) {
    order.push_back(c ^ r.a);
    glm::vec3 c0, c1;
    revellesChild(c, r.t0, r.t1, tm, c0, c1);
    c = revellesNextChild(c, c1);
  }
  return order;
}

}  // namespace passtrace
