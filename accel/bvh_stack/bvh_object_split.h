#pragma once
// The binned SAH object split (Wald 2007) of the SAH and SBVH builders: the
// centroids binned along each axis, every bin boundary a candidate; each
// reference goes whole to one side.

#include <span>
#include <vector>

#include "accel/bvh_stack/binary_bvh.h"
#include "accel/bvh_stack/bvh_build_driver.h"

namespace passtrace {

struct BvhObjectSplit {
  float cost = kInfinity;  // K_T + K_I (SA(L) N_L + SA(R) N_R) / SA(node); infinite: no valid split
  int axis = -1;
  uint32_t bin = 0;        // references in bins <= bin go left
  Aabb centroids;          // the binning's range
  Aabb left, right;        // the halves' boxes
  bool valid() const { return axis >= 0; }
};

// The cheapest binned object split of refs (within `box`).
BvhObjectSplit findObjectSplit(std::span<const BvhBuildRef> refs, const Aabb& box, const BvhStackConfig& config);
// Distributes refs as `split` says.
void applyObjectSplit(const BvhObjectSplit& split, std::span<const BvhBuildRef> refs, const BvhStackConfig& config,
                      std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right);

// K_I n: the SAH cost of making a leaf of n references.
inline float leafCost(size_t n, const BvhStackConfig& config) { return config.intersectionCost * float(n); }

}  // namespace passtrace
