#include "accel/bvh/bvh_traversal.h"

#include <limits>

namespace passtrace {

bool stepEscapeSequence(const SequenceView& seq, const Ray& ray, bool anyHit, EscapeCursor& cursor,
                        uint32_t maxSteps, TriangleTest test) {
  const glm::vec3 invDir = safeInverse(ray.direction);
  const glm::vec4* texels = seq.texels.data();
  const auto size = static_cast<uint32_t>(seq.texels.size());
  uint32_t idx = cursor.index;
  const auto boxTexels = uint32_t(boxTexelCount(seq.grid));
  const bool shared = !seq.sharedTriangles.empty();
  const GridRay gridRay = seq.grid ? seq.grid->ray(ray.origin, invDir) : GridRay{};
  for (uint32_t step = 0; step < maxSteps && idx < size; ++step) {
    const glm::vec4 t0 = texels[idx];
    ++cursor.stats.steps;
    if (t0.w >= 0.0f) {  // a box; w is its packed escape index
      const bool enter = seq.grid ? BoxGrid::intersects(gridRay, glm::vec3(t0), cursor.best.t)
                                  : intersectsBox(ray.origin, invDir, {glm::vec3(t0), glm::vec3(texels[idx + 1])},
                                                  cursor.best.t);
      idx = enter ? idx + boxTexels : unpackIndex(t0.w);
    } else {  // a triangle: v1 and v2 inline, or at 2 slot of the shared stream
      const glm::vec4* rest = shared ? &seq.sharedTriangles[2 * size_t(unpackIndex(-t0.w))] : &texels[idx + 1];
      ++cursor.stats.triangleTests;
      const Triangle tri{glm::vec3(t0), glm::vec3(rest[0]), glm::vec3(rest[1])};
      const bool found = intersectTriangle(ray.origin, ray.direction, tri, unpackIndex(rest[0].w), cursor.best, test);
      idx = (found && anyHit) ? size : idx + (shared ? 1 : 3);
    }
  }
  cursor.index = idx;
  return idx < size;
}

Hit traverseEscapeSequence(const SequenceView& seq, const Ray& ray, bool anyHit, RayStats* stats,
                           TriangleTest test) {
  EscapeCursor cursor;
  cursor.best.t = ray.tMax;
  stepEscapeSequence(seq, ray, anyHit, cursor, std::numeric_limits<uint32_t>::max(), test);
  if (stats) {
    stats->steps += cursor.stats.steps;
    stats->triangleTests += cursor.stats.triangleTests;
  }
  return cursor.best;
}

namespace {

struct RecursiveDescent {
  const Bvh& bvh;
  std::span<const Triangle> tris;
  glm::vec3 origin, direction, invDir;
  bool anyHit;
  TriangleTest test;
  Hit best;
  uint32_t steps = 0, triangleTests = 0;

  // Returns true when traversal must stop (an any-hit query found its hit).
  bool visit(uint32_t index) {
    const BvhNode& node = bvh.nodes[index];
    ++steps;
    if (node.isLeaf()) {
      ++triangleTests;
      intersectTriangle(origin, direction, tris[node.triangle], node.triangle, best, test);
      return anyHit && best.found();
    }
    if (!intersectsBox(origin, invDir, node.box, best.t)) return false;
    for (uint32_t c = 0; c < node.childCount; ++c)
      if (visit(bvh.children[node.firstChild + c])) return true;
    return false;
  }
};

}  // namespace

Hit traverseBvhRecursive(const Bvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                         RayStats* stats, TriangleTest test) {
  RecursiveDescent descent{bvh, tris, ray.origin, ray.direction, safeInverse(ray.direction), anyHit, test,
                           Hit{ray.tMax}};
  if (!bvh.nodes.empty()) descent.visit(0);
  if (stats) {
    stats->steps += descent.steps;
    stats->triangleTests += descent.triangleTests;
  }
  return descent.best;
}

}  // namespace passtrace
