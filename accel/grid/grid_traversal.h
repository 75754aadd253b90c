#pragma once
// CPU traversal of the uniform grid: Amanatides & Woo's 3D-DDA (thesis 7.2,
// Algorithm 1), visiting the cells the ray pierces in order and stopping at
// the first cell that holds a hit inside it.

#include <span>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"
#include "accel/grid/uniform_grid.h"

namespace passtrace {

// intersectsBox (geometry.h) that also returns the interval, from the same
// clipToBox: the parametric interval in which the ray is inside box, rays
// parallel to a slab included. The interval is written either way.
inline bool clipRayToBox(const glm::vec3& origin, const glm::vec3& invDir, const Aabb& box, float tBest,
                         float& tNear, float& tFar) {
  return clipToBox(origin, invDir, box, tNear, tFar) && tFar >= 0.0f && tNear < tBest;
}

// Starts from best = Hit{t = ray.tMax}. The ray is clipped to grid.bounds
// (clipRayToBox); the first cell is UniformGrid::cellOf the entry point
// (the origin when it is inside), so origins on cell or grid boundaries
// need no special case. Each visited cell tests all its triangles with
// intersectTriangle; traversal stops when best.t <= the cell's exit t (a hit
// inside the cell, or tMax reached), at the first hit with anyHit, or when
// the ray leaves the grid. Axes with one cell or a direction component
// parallel to the slabs (the intersectsBox rule) are never stepped along.
// The next boundary t on each axis is recomputed from the boundary
// coordinate at every step rather than accumulated from delta, so it never
// drifts. Triangles listed in several cells are tested once per cell (no
// mailboxing, as on the GPU). stats, when given, is added to: one step per
// cell visited, one test per triangle test. `test` picks the ray/triangle
// test (accel/geometry/triangle_test.h).
Hit traverseGrid(const UniformGrid& grid, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                 RayStats* stats = nullptr, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
