#pragma once
// The split BVH (Stich, Friedrich & Dietrich 2009): at each node the best
// binned object split, and where its halves overlap by more than sbvhAlpha
// of the root's area also the best spatial split (binned planes; references
// straddling a plane clipped into both halves). A straddling reference is
// kept whole on one side instead of split when that is cheaper (reference
// unsplitting). References grow to at most (1 + sbvhSplitBudget) times the
// triangles. The halves' boxes bound the clipped parts conservatively.

#include <span>

#include "accel/bvh_stack/binary_bvh.h"
#include "accel/bvh_stack/bvh_build_driver.h"

namespace passtrace {

BinaryBvh buildSbvh(std::span<const Triangle> tris, const BvhStackConfig& config = {});

// The parts of `ref` (a reference to `tri`) below and above the plane
// coordinate[axis] = plane, as boxes; a part the triangle does not reach is
// empty. Exposed for tests.
void splitReference(const Triangle& tri, const BvhBuildRef& ref, int axis, float plane, Aabb& below, Aabb& above);

}  // namespace passtrace
