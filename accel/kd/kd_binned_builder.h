#pragma once
// The binned SAH kd builder (seed 003 section 4.1, after Shevtsov et al.
// 2007): min-max binning. Per axis the node's voxel is cut into kKdBins equal
// bins; min-bins count the references whose clipped bounds start in a bin,
// max-bins those that end in it. At the boundary before bin b, an exclusive
// scan of the min-bins gives the references left of it and an inclusive scan
// of the max-bins from the far end those right of it, so the SAH of all
// 3 (kKdBins - 1) candidate planes costs one pass over the references plus
// O(kKdBins). The counts are estimates (a bound exactly on a boundary is
// binned to one side); the references are then sent to the children by the
// exact closed-voxel rule and straddlers re-clipped (kd_build_driver.h), so
// the tree has the exact builder's invariants and never loses a triangle.
//
// Choices the seed's extraction lost:
// - kKdBins = 64: the SAH of a plane is flat near its minimum, so evenly
//   spaced candidates cost little tree quality, and for large nodes the scan
//   is small beside the binning pass over the references. Measured with
//   16 / 32 / 64 bins (SAH cost of the bunny; of 1M spheres; 1M build time):
//   75.5 / 74.4 / 73.4; 92.5 / 90.8 / 89.4; 3.2 s of CPU for all three. A
//   node of n < kKdBins / 2 references uses the power of two at or above 2n
//   bins (at least 4): it has at most 2n distinct bounds, and the scan would
//   otherwise be most of its time (with 32 bins: a tenth of the 1M build).
// - K_T = 1, K_I = 1.5: the exact builder's KdBuildConfig defaults
//   (traversalCost, intersectionCost), so the two builders optimise, and
//   report (AccelStats::sahCost), the same cost.
// Flat triangles need no epsilon box (the seed grows them): the closed-voxel
// rule sends a triangle lying in a plane to both children.

#include <cstddef>
#include <span>

#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

inline constexpr int kKdBins = 64;

// Same contract as buildKdTree (the same KdBuildConfig and limits); only the
// plane search differs.
KdTree buildKdTreeBinned(std::span<const Triangle> tris, const KdBuildConfig& config = {});

}  // namespace passtrace
