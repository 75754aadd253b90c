#include "accel/octree/octree_stream_traversal.h"

#include <algorithm>
#include <limits>

#include "accel/octree/octree_revelles.h"
#include "accel/octree/octree_texels.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

// The child of `node` in stored octant `octant`, or -1 for an empty octant.
float childOf(const OctreeStreamData& d, uint32_t node, int octant) {
  return d.nodes[kOctreeNodeStride * node + 1 + uint32_t(octant >> 2)][octant & 3];
}

// The node the ray is at is finished: the next child of the innermost frame
// that has one left (empty octants skipped), or the end.
void advance(const OctreeStreamData& d, const RevellesRay& r, OctreeStreamCursor& c) {
  c.mode = OctreeStreamCursor::kModeDown;
  while (!c.frames.empty()) {
    OctreeStreamCursor::Frame& f = c.frames.back();
    const glm::vec3 tm = 0.5f * (f.t0 + f.t1);
    glm::vec3 c0, c1;
    revellesChild(f.current, f.t0, f.t1, tm, c0, c1);
    const int next = revellesNextChild(f.current, c1);
    if (next == kRevellesExit) {
      c.frames.pop_back();
      continue;
    }
    f.current = next;
    const float child = childOf(d, f.node, next ^ r.a);
    if (child >= 0.0f) {
      c.node = unpackIndex(child);
      return;
    }
  }
  c.done = true;
}

void step(const OctreeStreamData& d, const Ray& ray, const RevellesRay& r, bool anyHit, OctreeStreamCursor& c) {
  ++c.stats.steps;
  if (c.mode >= 0.0f) {
    const uint32_t entry = unpackIndex(c.mode);
    const float id = d.lists[entry >> 2][int(entry & 3u)];
    if (id < 0.0f) {  // the leaf is searched: a hit inside it ends the ray
      if (c.best.t <= c.leafExit) c.done = true;
      else advance(d, r, c);
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
  glm::vec3 t0 = r.t0, t1 = r.t1;
  if (!c.frames.empty()) {
    const OctreeStreamCursor::Frame& f = c.frames.back();
    revellesChild(f.current, f.t0, f.t1, 0.5f * (f.t0 + f.t1), t0, t1);
  }
  const float entry = std::max(std::max(t0.x, t0.y), t0.z);
  const float exit = std::min(std::min(t1.x, t1.y), t1.z);
  if (entry >= c.best.t) {  // every node after this one is entered later still
    c.done = true;
    return;
  }
  if (entry > exit || exit < 0.0f) {  // missed, or behind the origin
    advance(d, r, c);
    return;
  }
  const float tag = d.nodes[kOctreeNodeStride * c.node].x;
  if (tag >= 0.0f) {  // leaf with triangles
    c.mode = tag;
    c.leafExit = exit;
  } else if (tag > -1.5f) {  // empty leaf
    advance(d, r, c);
  } else {
    const int first = revellesFirstChild(t0, 0.5f * (t0 + t1));
    c.frames.push_back({c.node, t0, t1, first});
    const float child = childOf(d, c.node, first ^ r.a);
    if (child >= 0.0f) c.node = unpackIndex(child);
    else advance(d, r, c);
  }
}

}  // namespace

OctreeStreamCursor octreeStreamStart(const OctreeStreamData& d, const Ray& ray) {
  OctreeStreamCursor c;
  c.best.t = ray.tMax;
  c.done = d.nodes.empty();
  return c;
}

bool octreeStreamSteps(const OctreeStreamData& d, const Ray& ray, bool anyHit, OctreeStreamCursor& c,
                       uint32_t maxSteps) {
  const RevellesRay r = revellesStart(d.rootBox, ray.origin, ray.direction);
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) step(d, ray, r, anyHit, c);
  return !c.done;
}

Hit traverseOctreeStream(const OctreeStreamData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  OctreeStreamCursor c = octreeStreamStart(d, ray);
  octreeStreamSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
