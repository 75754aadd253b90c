#pragma once
// Traversal of the 8-wide BVH: the eight child boxes tested at once, hit
// children visited nearest first from an explicit stack, leaves tested a pack
// of four triangles at once (Möller–Trumbore; the watertight test one
// triangle at a time). Two builds of the same loop (wide_bvh_traverse.inc):
// AVX2 for CPUs that have it, chosen at run time, and portable scalar code.
// Both perform the same float operations in the same order as geometry.h's
// tests, so they return the same hits and counts as each other.
//
// RayStats: steps = inner nodes visited + triangles tested; triangleTests =
// real triangles tested (pack padding is not counted).

#include <span>

#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"
#include "accel/wide_bvh/wide_bvh.h"

namespace passtrace {

Hit traverseWideBvhScalar(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                          TriangleTest test, RayStats* stats);
// Only on CPUs where wideBvhAvx2Available().
Hit traverseWideBvhAvx2(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                        TriangleTest test, RayStats* stats);
bool wideBvhAvx2Available();
inline constexpr int kWidePacketMax = 64;  // rays per packet: one bit each in a 64-bit mask
// Up to kWidePacketMax rays (Möller–Trumbore only) as one packet sharing a stack; hits
// and stats have one entry per ray (stats are added to). AVX2 only, as above.
void traceWideBvhPacketAvx2(const WideBvh& bvh, std::span<const Ray> rays, bool anyHit, std::span<Hit> hits,
                            std::span<RayStats> stats);

}  // namespace passtrace
