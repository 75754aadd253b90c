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
// - kKdBins = 32: the SAH of a plane is flat near the optimum, so 32
//   candidates per axis lose a few percent of cost against the exact search
//   (measured on the bunny and 1M spheres, docs/design.md), while the scan
//   per node stays small beside the binning pass even for the millions of
//   small nodes of a 10M-triangle tree. Below 2 x kKdBins references a node
//   has fewer distinct bounds than bins and binning is no longer cheaper,
//   but it is kept there too so that the builder is binned throughout.
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

inline constexpr int kKdBins = 32;

// Same contract as buildKdTree (the same KdBuildConfig and limits); only the
// plane search differs.
KdTree buildKdTreeBinned(std::span<const Triangle> tris, const KdBuildConfig& config = {});

}  // namespace passtrace
