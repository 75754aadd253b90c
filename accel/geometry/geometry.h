#pragma once
// Rays, hits, boxes and triangles, with the two intersection tests every
// accelerator uses. kernels_glsl/intersect.glsl performs the same operations
// in the same order, so the CPU and GPU paths agree to the last bit wherever
// the compilers keep IEEE order (ties are compared with a tolerance in tests).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace passtrace {

inline constexpr uint32_t kNoHit = 0xFFFFFFFFu;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};
  float tMax = kInfinity;  // hits at or beyond tMax are ignored
};

// Barycentric u, v weight the triangle's second and third vertex.
struct Hit {
  float t = kInfinity;
  float u = 0.0f;
  float v = 0.0f;
  uint32_t id = kNoHit;
  bool found() const { return id != kNoHit; }
};

struct Aabb {
  glm::vec3 min{kInfinity};
  glm::vec3 max{-kInfinity};

  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
  float surfaceArea() const {
    if (empty()) return 0.0f;
    const glm::vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

struct Triangle {
  glm::vec3 v0, v1, v2;
  Aabb bounds() const {
    Aabb b;
    b.extend(v0);
    b.extend(v1);
    b.extend(v2);
    return b;
  }
  glm::vec3 centroid() const { return (v0 + v1 + v2) * (1.0f / 3.0f); }
  glm::vec3 geometricNormal() const { return glm::cross(v1 - v0, v2 - v0); }
};

// 1/d with zero components replaced by a tiny signed value, so the slab test
// never computes 0 * inf = NaN for rays parallel to a slab.
inline glm::vec3 safeInverse(const glm::vec3& d) {
  auto inv = [](float x) {
    const float tiny = 1e-20f;
    return 1.0f / (std::fabs(x) < tiny ? (x < 0.0f ? -tiny : tiny) : x);
  };
  return {inv(d.x), inv(d.y), inv(d.z)};
}

// Slab test: does the ray enter [box.min, box.max] before tBest (and not
// entirely behind the origin)? A ray parallel to a slab (|invDir| above
// kParallelInverse, i.e. a direction component below 1e-19) is inside that
// slab for all t or for none: with the tiny stand-in alone an origin lying
// exactly on the max face would give the interval [-huge, 0] and miss.
inline constexpr float kParallelInverse = 1e19f;

// The interval [tNear, tFar] where the ray's line is inside the box; false
// when it is empty. kernels_glsl/clip_box.glsl computes the same.
// `parallel` names the slabs the ray is parallel to: given apart for rays whose
// inverse direction is scaled (accel/bvh/box_grid.h's grid units).
inline bool clipToBox(const glm::vec3& origin, const glm::vec3& invDir, const glm::bvec3& parallel, const Aabb& box,
                      float& tNear, float& tFar) {
  const glm::vec3 t0 = (box.min - origin) * invDir;
  const glm::vec3 t1 = (box.max - origin) * invDir;
  glm::vec3 tSmall = glm::min(t0, t1);
  glm::vec3 tLarge = glm::max(t0, t1);
  for (int k = 0; k < 3; ++k) {
    if (parallel[k]) {
      const bool inside = origin[k] >= box.min[k] && origin[k] <= box.max[k];
      tSmall[k] = inside ? -kInfinity : kInfinity;
      tLarge[k] = inside ? kInfinity : -kInfinity;
    }
  }
  tNear = std::max(std::max(tSmall.x, tSmall.y), tSmall.z);
  tFar = std::min(std::min(tLarge.x, tLarge.y), tLarge.z);
  return tNear <= tFar;
}

inline glm::bvec3 parallelSlabs(const glm::vec3& invDir) {
  return glm::greaterThan(glm::abs(invDir), glm::vec3(kParallelInverse));
}

inline bool clipToBox(const glm::vec3& origin, const glm::vec3& invDir, const Aabb& box, float& tNear, float& tFar) {
  return clipToBox(origin, invDir, parallelSlabs(invDir), box, tNear, tFar);
}

// The BVHs' box test is conservative (Ize, "Robust BVH Ray Traversal", JCGT
// 2013, as in pbrt-v4): each slab t carries up to 3 roundings, so the exit t
// is enlarged by 2 gamma(3) = 3 ulps of 1 before comparing. Without it a ray
// that passes exactly through a box corner, such as a ray aimed at a mesh
// vertex, can miss every box around the vertex and slip through a closed
// mesh (tests/gl/watertight_test.cpp found this).
inline constexpr float kRobustExitScale = 1.0f + 3.0f * 0x1p-23f;

inline bool intersectsBox(const glm::vec3& origin, const glm::vec3& invDir, const Aabb& box, float tBest) {
  float tNear, tFar;
  clipToBox(origin, invDir, box, tNear, tFar);
  const float tExit = tFar * kRobustExitScale;
  return tNear <= tExit && tExit >= 0.0f && tNear < tBest;
}

// Möller–Trumbore, two-sided. Updates `best` and returns true when the
// triangle is hit strictly in front of the origin and strictly before best.t.
inline bool intersectTriangle(const glm::vec3& origin, const glm::vec3& dir, const Triangle& tri,
                              uint32_t id, Hit& best) {
  const glm::vec3 e1 = tri.v1 - tri.v0;
  const glm::vec3 e2 = tri.v2 - tri.v0;
  const glm::vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(p, e1);
  if (det == 0.0f) return false;  // ray parallel to the plane, or a degenerate triangle
  const float invDet = 1.0f / det;
  const glm::vec3 tvec = origin - tri.v0;
  const float u = glm::dot(p, tvec) * invDet;
  const glm::vec3 q = glm::cross(tvec, e1);
  const float v = glm::dot(q, dir) * invDet;
  const float t = glm::dot(q, e2) * invDet;
  if (!(u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f && t < best.t)) return false;
  best = Hit{t, u, v, id};
  return true;
}

}  // namespace passtrace
