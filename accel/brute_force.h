#pragma once
// Every triangle, in scene order: the reference the accelerators are checked
// against (ties at equal t go to the lowest scene index).

#include <span>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

// Starts from best = Hit{t = ray.tMax}; with anyHit, stops at the first hit.
// stats, when given, is added to: one step and one test per triangle.
// `test` picks the ray/triangle test (accel/geometry/triangle_test.h).
Hit intersectBruteForce(std::span<const Triangle> tris, const Ray& ray, bool anyHit, RayStats* stats = nullptr,
                        TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
