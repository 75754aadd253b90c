#pragma once
// The binned SAH builder: at every node the cheapest binned object split
// (bvh_object_split.h); a node of at most maxLeafSize references becomes a
// leaf when that is cheaper by the SAH.

#include <span>

#include "accel/bvh_stack/binary_bvh.h"

namespace passtrace {

BinaryBvh buildBinnedSah(std::span<const Triangle> tris, const BvhStackConfig& config = {});

}  // namespace passtrace
