#pragma once
// Boxes quantized to one scene-wide grid, a box in one RGBA texel: bvh-octant
// keeps eight copies of its boxes (one sequence per ray octant), and full
// precision (two texels a box) made them 384 of its 607 bytes per triangle
// on the stream path.
//
// Each axis has 2^15 grid planes, origin + q * step for q in [0, 32767], step
// a power of two. A box's planes are rounded outwards, at least step / 256
// beyond the exact box, so the quantized box encloses it with room to spare.
//
// The slab test runs in grid units (intersects): the ray's origin and inverse
// direction are mapped once per ray, (o - origin) / step and invDir * step,
// and a box's planes are then its integers q as floats, with no decoding per
// box. Measured on the bunny (bvh-octant-fused, 512², eight rounds): 14 % faster
// than full-precision boxes of two texels, while decoding the planes to world
// units first was 6 % slower (docs/bench-speed/NOTES.md). t along the grid ray
// is t along the world ray. Why it stays conservative: the power-of-two step
// makes the scaling exact, so the only new rounding is o - origin's, at most
// half an ulp of |o - origin|; for origins inside the grid that is under
// 2^-9 grid units, which the step / 256 margin covers, and for origins
// farther away it is within the rounding of t that the exit's slack
// (kGridExitScale, one ulp of 1 more than intersectsBox's) absorbs.
//
// In the texel, axis a's float holds lo << 15 | hi in bits 0-29 and bit 30
// the complement of bit 29: sign 0 and exponent 64-191, a normal float that no
// upload or fetch can flush or canonicalize (kernels read it back with
// floatBitsToUint and mask bit 30 off). w stays free for the escape index.
// kernels_glsl/bvh/box_grid.glsl is the GPU's side, operation for operation.

#include <cstdint>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace {

// A ray in grid units (BoxGrid::ray): the same t reaches the same point.
struct GridRay {
  glm::vec3 origin;
  glm::vec3 invDir;
  glm::bvec3 parallel;  // from the world inverse: scaling moves it past kParallelInverse
};

inline constexpr float kGridExitScale = 1.0f + 4.0f * 0x1p-23f;

struct BoxGrid {
  static constexpr uint32_t kMaxPlane = (1u << 15) - 1;

  glm::vec3 origin{0.0f};
  glm::vec3 step{1.0f};     // powers of two, normal floats
  glm::vec3 invStep{1.0f};  // 1 / step, exact

  // The grid around `bounds` (a tree's root box), a margin beyond each face:
  // step the least power of two, at least 2^-100 and 2^-20 of the widest
  // axis, for which origin = min - step and plane kMaxPlane both lie
  // step / 256 or more outside the bounds.
  static BoxGrid over(const Aabb& bounds);

  // Plane q of `axis` in world units, exactly (double holds it).
  double plane(int axis, uint32_t q) const { return double(origin[axis]) + double(q) * double(step[axis]); }
  // The texel's xyz for `box` (enclosing it by the margin); w is the caller's.
  glm::vec3 encode(const Aabb& box) const;
  // The planes (lo, hi) of a texel in grid units.
  static Aabb gridPlanes(const glm::vec3& xyz);

  GridRay ray(const glm::vec3& rayOrigin, const glm::vec3& invDir) const {
    return {(rayOrigin - origin) * invStep, invDir * step, parallelSlabs(invDir)};
  }
  // intersectsBox in grid units, with kGridExitScale's slack.
  static bool intersects(const GridRay& ray, const glm::vec3& xyz, float tBest) {
    float tNear, tFar;
    clipToBox(ray.origin, ray.invDir, ray.parallel, gridPlanes(xyz), tNear, tFar);
    const float tExit = tFar * kGridExitScale;
    return tNear <= tExit && tExit >= 0.0f && tNear < tBest;
  }
};

}  // namespace passtrace
