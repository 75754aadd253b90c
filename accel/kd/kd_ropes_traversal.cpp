#include "accel/kd/kd_ropes_traversal.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stream/texel_address.h"

namespace passtrace {
namespace {

float listEntry(const KdRopesData& d, uint32_t entry) { return d.lists[entry >> 2][int(entry & 3u)]; }

// The leaf at c.node is searched: leave it through its nearest face on the side the ray heads to.
void leaveLeaf(const KdRopesData& d, const Ray& ray, const glm::vec3& invDir, KdRopesCursor& c) {
  const glm::vec3 lo(d.nodes[c.node + 2]), hi(d.nodes[c.node + 3]);
  glm::vec3 t;
  for (int k = 0; k < 3; ++k) {
    const float side = ray.direction[k] >= 0.0f ? hi[k] : lo[k];
    // A ray parallel to a slab never leaves through it (as clipToBox).
    t[k] = std::fabs(invDir[k]) > kParallelInverse ? kInfinity : (side - ray.origin[k]) * invDir[k];
  }
  const int axis = t.x <= t.y && t.x <= t.z ? 0 : (t.y <= t.z ? 1 : 2);
  const float tExit = t[axis];
  if (c.best.t <= tExit || tExit >= c.sceneMax) {
    c.done = true;
    return;
  }
  const float rope = d.nodes[c.node + (ray.direction[axis] >= 0.0f ? 1 : 0)][axis];
  if (rope < 0.0f) {
    c.done = true;
    return;
  }
  c.node = unpackIndex(rope);
  c.tEntry = std::max(c.tEntry, tExit);
  c.mode = KdRopesCursor::kModeDown;
}

void step(const KdRopesData& d, const Ray& ray, const glm::vec3& invDir, bool anyHit, KdRopesCursor& c) {
  if (c.stats.steps >= d.maxSteps) {  // the robustness bound
    c.done = true;
    return;
  }
  ++c.stats.steps;
  if (c.mode >= 0.0f) {
    const uint32_t entry = unpackIndex(c.mode);
    const float id = listEntry(d, entry);
    if (id < 0.0f) {
      leaveLeaf(d, ray, invDir, c);
    } else {
      ++c.stats.triangleTests;
      const uint32_t t = unpackIndex(id);
      const Triangle tri{glm::vec3(d.triangles[3 * t]), glm::vec3(d.triangles[3 * t + 1]),
                         glm::vec3(d.triangles[3 * t + 2])};
      const bool found = intersectTriangle(ray.origin, ray.direction, tri, t, c.best, d.triangleTest);
      c.done = found && anyHit;
      c.mode = packIndex(entry + 1);
    }
    return;
  }
  const glm::vec4 node = d.nodes[c.node];
  if (node.w < -1.5f) {  // internal: w = -(axis + 2)
    const int axis = int(-node.w) - 2;
    const float o = ray.origin[axis];
    // An origin on the plane, or a ray parallel to it, never crosses it.
    const bool never = o == node.y || std::fabs(invDir[axis]) > kParallelInverse;
    const float tSplit = never ? kInfinity : (node.y - o) * invDir[axis];
    const bool belowFirst = o < node.y || (o == node.y && ray.direction[axis] <= 0.0f);
    // The entry point lies beyond the plane once the ray has crossed it (0 <= tSplit <= tEntry).
    const bool crossed = tSplit >= 0.0f && tSplit <= c.tEntry;
    c.node = belowFirst != crossed ? c.node + 1 : unpackIndex(node.x);
  } else if (node.w >= 0.0f) {  // leaf with triangles
    c.mode = node.w;
  } else {  // empty leaf
    leaveLeaf(d, ray, invDir, c);
  }
}

}  // namespace

uint64_t kdRopesMaxSteps(size_t leaves, uint32_t depth, size_t listEntries) {
  return 2 * (uint64_t(leaves) + 1) * (uint64_t(depth) + 2) + uint64_t(listEntries);
}

KdRopesCursor kdRopesStart(const KdRopesData& d, const Ray& ray) {
  KdRopesCursor c;
  c.best.t = ray.tMax;
  float tNear, tFar;
  const bool inside = clipToBox(ray.origin, safeInverse(ray.direction), d.sceneBox, tNear, tFar);
  c.tEntry = std::max(tNear, 0.0f);
  c.sceneMax = std::min(tFar, ray.tMax);
  c.done = !(inside && c.tEntry <= c.sceneMax) || d.nodes.empty();
  return c;
}

bool kdRopesSteps(const KdRopesData& d, const Ray& ray, bool anyHit, KdRopesCursor& c, uint32_t maxSteps) {
  const glm::vec3 invDir = safeInverse(ray.direction);
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) step(d, ray, invDir, anyHit, c);
  return !c.done;
}

Hit traverseKdRopes(const KdRopesData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  KdRopesCursor c = kdRopesStart(d, ray);
  kdRopesSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
