#pragma once
// The middle-cut builder: each node split at the middle of its centroid
// box's largest axis (the median when that leaves a side empty), until at
// most leafSize references remain. No cost model: the baseline of the
// SAH builders.

#include <span>

#include "accel/bvh_stack/binary_bvh.h"

namespace passtrace {

BinaryBvh buildMiddleCut(std::span<const Triangle> tris, const BvhStackConfig& config = {});

}  // namespace passtrace
