#pragma once
// The top-down build every stack-BVH builder shares: references (a triangle
// and a box around its part in the node) are split node by node with an
// explicit work stack until a node becomes a leaf; the builders only choose
// the splits (a BvhSplitter).

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "accel/bvh_stack/binary_bvh.h"

namespace passtrace {

struct BvhBuildRef {
  Aabb box;           // bounds the triangle's part in the node (the whole triangle unless clipped)
  uint32_t triangle;  // index in the scene
};

// Splits `refs` (whose boxes' union is `box`, more than leafSize of them, at
// level `depth`, the root 1) into two non-empty halves, or returns false
// for a leaf. May reorder refs.
using BvhSplitter = std::function<bool(std::vector<BvhBuildRef>& refs, const Aabb& box, uint32_t depth,
                                       std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right)>;

// The references of every triangle with finite vertices (others can never
// be hit), in scene order.
std::vector<BvhBuildRef> bvhBuildRefs(std::span<const Triangle> tris);

// Builds with `split`; a splitter that leaves a half empty falls back to the
// median split. A threadSafeSplitter (one without state) is called from
// several threads: large subtrees are built in parallel (oneTBB), with the
// same tree as one thread would make.
BinaryBvh buildBinaryBvh(std::span<const Triangle> tris, const BvhStackConfig& config, const BvhSplitter& split,
                         bool threadSafeSplitter = false);

// The centroid box of refs' boxes.
Aabb bvhCentroidBox(std::span<const BvhBuildRef> refs);

// Splits at the median centroid of the centroid box's largest axis: always
// two non-empty halves of sizes n/2 and n - n/2 (n >= 2).
void bvhMedianSplit(std::vector<BvhBuildRef>& refs, std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right);

}  // namespace passtrace
