#include "accel/kd/kd_stream_traversal.h"

#include <limits>

#include "accel/kd/kd_compact_node.h"
#include "accel/reference_lists.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

uint32_t stride(const KdStreamData& d) { return d.variant == KdStreamVariant::Backtrack ? 3u : 1u; }

// A node's (first) texel in the restart layout's form, decoding compact nodes.
glm::vec4 nodeTexel(const KdStreamData& d, uint32_t node) {
  if (d.variant == KdStreamVariant::Compact) return kdCompactNodeTexel(d.nodes, node);
  return d.nodes[stride(d) * node];
}

float listEntry(const KdStreamData& d, uint32_t entry) { return d.lists[entry >> 2][int(entry & 3u)]; }

void leafFinished(const KdStreamData& d, KdStreamCursor& c, const glm::vec4& leaf) {
  if (c.best.t <= c.tMax || c.tMax >= c.sceneMax) {
    c.done = true;
    return;
  }
  if (d.variant == KdStreamVariant::Backtrack) {
    c.tMin = c.tMax;
    c.tMax = c.sceneMax;
    if (leaf.z < 0.0f) {
      c.done = true;
    } else {
      c.node = unpackIndex(leaf.z);
      c.mode = KdStreamCursor::kModeUp;
    }
    return;
  }
  c.mode = KdStreamCursor::kModeDown;
  if (!c.stack.empty()) {  // pop the latest far child
    const KdCircularStack::Entry e = c.stack.pop();
    c.node = e.node;
    c.tMin = e.tMin;
    c.tMax = e.tMax;
    return;
  }
  // Restart: descend again over what is left of the ray.
  c.tMin = c.tMax;
  c.tMax = c.sceneMax;
  c.node = c.root;
  c.pushDown = true;
}


void step(const KdStreamData& d, const Ray& ray, const glm::vec3& invDir, bool anyHit, KdStreamCursor& c) {
  ++c.stats.steps;
  if (c.mode >= 0.0f) {
    const uint32_t entry = unpackIndex(c.mode);
    const float id = listEntry(d, entry);
    if (id < 0.0f) {
      leafFinished(d, c, nodeTexel(d, c.node));
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
  if (c.mode == KdStreamCursor::kModeUp) {
    const Aabb box{glm::vec3(d.nodes[stride(d) * c.node + 1]), glm::vec3(d.nodes[stride(d) * c.node + 2])};
    float tNear, tFar;
    clipToBox(ray.origin, invDir, box, tNear, tFar);
    if (tFar > c.tMin) {
      c.mode = KdStreamCursor::kModeDown;
      c.tMax = std::min(tFar, c.sceneMax);
    } else {
      const float parent = d.nodes[stride(d) * c.node].z;
      if (parent < 0.0f) c.done = true;
      else c.node = unpackIndex(parent);
    }
    return;
  }
  const glm::vec4 node = nodeTexel(d, c.node);
  if (node.w < -1.5f) {  // internal: w = -(axis + 2)
    const int axis = int(-node.w) - 2;
    const float split = node.y;
    const float o = ray.origin[axis];
    // An origin on the plane never crosses it: it stays on the side it heads to.
    const float tSplit = o == split ? kInfinity : (split - o) * invDir[axis];
    const bool belowFirst = o < split || (o == split && ray.direction[axis] <= 0.0f);
    const uint32_t right = unpackIndex(node.x);
    const uint32_t first = belowFirst ? c.node + 1 : right;
    const uint32_t second = belowFirst ? right : c.node + 1;
    if (tSplit < 0.0f || tSplit >= c.tMax) {
      c.node = first;
    } else if (tSplit <= c.tMin) {
      c.node = second;
    } else {  // both children: the near one now, the far one later
      // The far child's interval ends at the old tMax (the digest's Algorithm 1 fix).
      if (kdHasStack(d.variant)) c.stack.push({second, tSplit, c.tMax});
      c.pushDown = false;
      c.node = first;
      c.tMax = tSplit;
    }
    // The ray's rest lies in this child's voxel: later restarts can begin here.
    if (kdRestartsFromPushDownRoot(d.variant) && c.pushDown) c.root = c.node;
  } else if (node.w >= 0.0f) {  // leaf with triangles
    c.mode = node.w;
  } else {  // empty leaf
    leafFinished(d, c, node);
  }
}

}  // namespace

KdStreamCursor kdStreamStart(const KdStreamData& d, const Ray& ray) {
  KdStreamCursor c;
  c.best.t = ray.tMax;
  float tNear, tFar;
  const bool inside = clipToBox(ray.origin, safeInverse(ray.direction), d.sceneBox, tNear, tFar);
  c.tMin = std::max(tNear, 0.0f);
  c.tMax = std::min(tFar, ray.tMax);
  c.sceneMax = c.tMax;
  c.done = !(inside && c.tMin <= c.tMax) || d.nodes.empty();
  if (kdHasStack(d.variant)) c.stack = KdCircularStack(d.stackSize);
  return c;
}

bool kdStreamSteps(const KdStreamData& d, const Ray& ray, bool anyHit, KdStreamCursor& c, uint32_t maxSteps) {
  const glm::vec3 invDir = safeInverse(ray.direction);
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) step(d, ray, invDir, anyHit, c);
  return !c.done;
}

Hit traverseKdStream(const KdStreamData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  KdStreamCursor c = kdStreamStart(d, ray);
  kdStreamSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
