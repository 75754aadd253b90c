#pragma once
// A cone query (seed 000, Wiche & Kuri 2020): apex S, unit axis v,
// half-angle alpha (0 <= alpha < 90 degrees). A query returns the distinct
// triangles the cone meets, nearest first by their distance along the axis,
// up to maxHits of them (0 = all). [tNear, tFar] clips the axis: a query can
// be resumed past the last list's farthest entry (tNear = that t, next float).

#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

struct Cone {
  glm::vec3 apex{0.0f};
  glm::vec3 axis{0.0f, 0.0f, 1.0f};  // unit length
  float halfAngle = 0.0f;            // radians, in [0, pi/2)
};

struct ConeQueryConfig {
  uint32_t maxHits = 0;      // --cone-max: keep the n nearest; 0 = every triangle met
  float tNear = 0.0f;        // triangles nearer than this along the axis are skipped
  float tFar = kInfinity;    // ...and farther than this
  // --cone-nodes sorted: the BVH visits nodes in order of their nearest axis
  // distance (a heap) and stops at the first beyond the cut-off (seed 000's
  // node-sorted traversal); false: the stack, nearer child first. The
  // kd-tree's traversal is the stack either way.
  bool sortedNodes = false;
};

struct ConeHit {
  float t;      // distance along the axis of the triangle's nearest point inside the cone (cone_tests.h)
  uint32_t id;  // scene index
};

// Per query: the sorted hit list and the work done (the seed's "nodes" and
// "intersections": triangle references met in leaves, before any test).
struct ConeResult {
  std::vector<ConeHit> hits;  // nearest first; ties broken by id
  uint32_t nodes = 0;         // nodes visited
  uint32_t triangleTests = 0; // triangle references met in visited leaves
  uint32_t count() const { return uint32_t(hits.size()); }
};

}  // namespace passtrace
