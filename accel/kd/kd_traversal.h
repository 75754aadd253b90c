#pragma once
// Front-to-back stack traversal of a kd-tree on the CPU (thesis section 8.2,
// made iterative): the ray's [tNear, tFar] interval is clipped to the root
// voxel and cut at each split plane; the far child waits on a fixed-size
// stack (a tree has at most kKdDepthLimit splits per path) while the near
// one is walked, so leaves are visited in the order the ray pierces them.
//
// Special cases, handled explicitly rather than left to infinities:
//  - a direction component that is zero (or below 1e-19, the threshold
//    intersectsBox treats as parallel) along the split axis: the ray visits
//    only the side its origin is on, and both children, left first, with
//    the same interval, when the origin lies exactly on the plane;
//  - an origin on the plane with a nonzero component: tSplit is 0 and the
//    ray visits only the side it moves into.
// A waiting node is skipped once the best hit is no farther than where the
// ray enters it (best.t <= its tNear), which for the usual front-to-back
// stack means the ray is done when best.t <= the exit t of the leaf just
// tested; the parallel case above puts nodes with equal intervals on the
// stack, so every waiting node is checked rather than stopping at the
// first. With anyHit the walk stops at the first hit.
//
// Starts from best = Hit{t = ray.tMax}; hits at or beyond tMax are ignored.
// stats, when given, is added to: one step per node visited (internal or
// leaf) and one triangle test per reference tested. `test` picks the
// ray/triangle test (accel/geometry/triangle_test.h).

#include <span>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/kd/kd_tree.h"
#include "accel/traversal_stats.h"

namespace passtrace {

Hit traverseKdTree(const KdTree& tree, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                   RayStats* stats = nullptr, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
