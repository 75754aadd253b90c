#include "accel/bih/bih_stream_traversal.h"

#include <cmath>
#include <limits>

#include "stream/texel_address.h"

namespace passtrace {
namespace {

// One rounded product each, exact for 0 and infinities (no inf - inf).
float widenUp(float t) { return t * (t > 0.0f ? 1.0f + kBihSlack : 1.0f - kBihSlack); }
float widenDown(float t) { return t * (t > 0.0f ? 1.0f - kBihSlack : 1.0f + kBihSlack); }

// The leaf or the culled node is finished: the latest stacked child, or the end.
void popOrDone(BihStreamCursor& c) {
  c.mode = BihStreamCursor::kModeDown;
  if (c.stack.empty()) {
    c.done = true;
    return;
  }
  const BihStreamCursor::Entry e = c.stack.back();
  c.stack.pop_back();
  c.node = e.node;
  c.tMin = e.tMin;
  c.tMax = e.tMax;
}

void step(const BihStreamData& d, const Ray& ray, const glm::vec3& invDir, bool anyHit, BihStreamCursor& c) {
  ++c.stats.steps;
  if (c.mode >= 0.0f) {
    const uint32_t entry = unpackIndex(c.mode);
    const float id = d.lists[entry >> 2][int(entry & 3u)];
    if (id < 0.0f) {
      popOrDone(c);
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
  // Children beyond the current hit are skipped.
  const float tEnd = std::min(c.tMax, c.best.t);
  if (c.tMin > tEnd) {
    popOrDone(c);
    return;
  }
  const glm::vec4 node = d.nodes[c.node];
  if (node.w >= 0.0f) {  // leaf with triangles
    c.mode = node.w;
    return;
  }
  if (node.w > -1.5f) {  // empty leaf
    popOrDone(c);
    return;
  }
  const int axis = int(-node.w) - 2;
  const float o = ray.origin[axis], inv = invDir[axis];
  // Each child's part of [tMin, tEnd]: [lo[i], hi[i]], 0 left, 1 right.
  float lo[2] = {c.tMin, c.tMin}, hi[2] = {tEnd, tEnd};
  if (std::fabs(inv) > kParallelInverse) {  // parallel to the planes: in a child's slab for all t or none
    if (!(o <= node.y)) hi[0] = -kInfinity;
    if (!(o >= node.z)) hi[1] = -kInfinity;
  } else {
    const float tLeft = (node.y - o) * inv, tRight = (node.z - o) * inv;
    if (inv > 0.0f) {
      hi[0] = std::min(hi[0], widenUp(tLeft));
      lo[1] = std::max(lo[1], widenDown(tRight));
    } else {
      lo[0] = std::max(lo[0], widenDown(tLeft));
      hi[1] = std::min(hi[1], widenUp(tRight));
    }
  }
  const int nearSide = inv > 0.0f ? 0 : 1;
  const uint32_t child[2] = {c.node + 1, unpackIndex(node.x)};
  const bool visitNear = lo[nearSide] <= hi[nearSide], visitFar = lo[1 - nearSide] <= hi[1 - nearSide];
  if (visitNear && visitFar) c.stack.push_back({child[1 - nearSide], lo[1 - nearSide], hi[1 - nearSide]});
  if (visitNear || visitFar) {
    const int side = visitNear ? nearSide : 1 - nearSide;
    c.node = child[side];
    c.tMin = lo[side];
    c.tMax = hi[side];
  } else {
    popOrDone(c);  // the ray passes through the gap between the planes
  }
}

}  // namespace

BihStreamCursor bihStreamStart(const BihStreamData& d, const Ray& ray) {
  BihStreamCursor c;
  c.best.t = ray.tMax;
  float tNear, tFar;
  clipToBox(ray.origin, safeInverse(ray.direction), d.sceneBox, tNear, tFar);
  c.tMin = std::max(widenDown(tNear), 0.0f);
  c.tMax = std::min(widenUp(tFar), ray.tMax);
  c.done = !(c.tMin <= c.tMax) || d.nodes.empty();
  return c;
}

bool bihStreamSteps(const BihStreamData& d, const Ray& ray, bool anyHit, BihStreamCursor& c, uint32_t maxSteps) {
  const glm::vec3 invDir = safeInverse(ray.direction);
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) step(d, ray, invDir, anyHit, c);
  return !c.done;
}

Hit traverseBihStream(const BihStreamData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  BihStreamCursor c = bihStreamStart(d, ray);
  bihStreamSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
