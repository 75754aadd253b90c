#include "accel/bvh_stack/bvh_stack_traversal.h"

#include <limits>
#include <stdexcept>

#include "accel/bvh_stack/bvh_stack_texels.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

// Next stacked child the ray still reaches before its hit; done when none.
void pop(BvhStackCursor& c) {
  while (!c.stack.empty()) {
    const BvhStackEntry e = c.stack.back();
    c.stack.pop_back();
    if (e.tNear < c.best.t) {
      c.link = e.link;
      c.count = e.count;
      return;
    }
  }
  c.done = true;
}

// Whether the ray enters the child box of slot `lo`/`hi` texels before its
// hit (intersectsBox's test), and where.
bool enters(const Ray& ray, const glm::vec3& invDir, const glm::vec4& lo, const glm::vec4& hi, float tBest,
            float& tNear) {
  if (lo.w < 0.0f) return false;  // absent slot
  float tFar;
  clipToBox(ray.origin, invDir, Aabb{glm::vec3(lo), glm::vec3(hi)}, tNear, tFar);
  const float tExit = tFar * kRobustExitScale;
  return tNear <= tExit && tExit >= 0.0f && tNear < tBest;
}

void step(const BvhStackData& d, const Ray& ray, const glm::vec3& invDir, bool anyHit, BvhStackCursor& c) {
  ++c.stats.steps;
  if (c.count > 0) {  // the next reference of a leaf
    const uint32_t entry = c.link;
    const uint32_t t = unpackIndex(d.references[entry >> 2][int(entry & 3u)]);
    ++c.stats.triangleTests;
    const Triangle tri{glm::vec3(d.triangles[3 * t]), glm::vec3(d.triangles[3 * t + 1]),
                       glm::vec3(d.triangles[3 * t + 2])};
    const bool found = intersectTriangle(ray.origin, ray.direction, tri, t, c.best, d.triangleTest);
    if (found && anyHit) {
      c.done = true;
      return;
    }
    c.link = entry + 1;
    if (--c.count == 0) pop(c);
    return;
  }
  const uint32_t base = kBvhStackNodeTexels * c.link;
  float t0 = 0, t1 = 0;
  const bool hit0 = enters(ray, invDir, d.nodes[base], d.nodes[base + 1], c.best.t, t0);
  const bool hit1 = enters(ray, invDir, d.nodes[base + 2], d.nodes[base + 3], c.best.t, t1);
  const auto enter = [&](uint32_t slot) {
    c.link = unpackIndex(d.nodes[base + 2 * slot].w);
    c.count = uint32_t(d.nodes[base + 2 * slot + 1].w);
  };
  if (hit0 && hit1) {
    const uint32_t nearSlot = t0 <= t1 ? 0 : 1, farSlot = 1 - nearSlot;
    if (c.stack.size() >= d.stackSize) throw std::logic_error("bvh-stack: traversal stack overflow");
    c.stack.push_back({unpackIndex(d.nodes[base + 2 * farSlot].w), uint32_t(d.nodes[base + 2 * farSlot + 1].w),
                       farSlot == 0 ? t0 : t1});
    enter(nearSlot);
  } else if (hit0 || hit1) {
    enter(hit0 ? 0 : 1);
  } else {
    pop(c);
  }
}

}  // namespace

BvhStackCursor bvhStackStart(const BvhStackData& d, const Ray& ray) {
  BvhStackCursor c;
  c.best.t = ray.tMax;
  c.done = d.nodes.empty();
  c.stack.reserve(d.stackSize);
  return c;
}

bool bvhStackSteps(const BvhStackData& d, const Ray& ray, bool anyHit, BvhStackCursor& c, uint32_t maxSteps) {
  const glm::vec3 invDir = safeInverse(ray.direction);
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) step(d, ray, invDir, anyHit, c);
  return !c.done;
}

Hit traverseBvhStack(const BvhStackData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  BvhStackCursor c = bvhStackStart(d, ray);
  bvhStackSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
