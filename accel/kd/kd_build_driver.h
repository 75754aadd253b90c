#pragma once
// What the two SAH kd builders share: the node loop. A builder supplies only
// how a node's best plane is found (kd_tree_builder.cpp: every clipped
// triangle bound a candidate; kd_binned_builder.cpp: bin boundaries); the
// driver decides leaf or split (limits and the leaf-cheaper rule), sends each
// triangle to the child voxels it touches (clipping straddlers to them again:
// Havran's split clipping, seed 003 Algorithm 8), and lays the tree out
// depth-first.
//
// Both cores: a node of kKdParallelNodeRefs references or more builds its two
// children as parallel oneTBB tasks, and nodes of kKdParallelSweepRefs or
// more partition (and bin) their references in parallel. Each task builds
// its subtree into its own arrays; the pieces are then copied into the one
// depth-first layout in tree order, so the tree is the same for any thread
// count (the split finders' sums over references are integers or fixed-order).
// The build runs in the caller's oneTBB arena: tbb::task_arena or
// tbb::global_control set the thread count (passtrace's --threads).

#include <cstddef>
#include <cstdint>
#include <span>

#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

inline constexpr size_t kKdParallelNodeRefs = 2048;
inline constexpr size_t kKdParallelSweepRefs = 65536;
// Large nodes are cut into this many fixed chunks for parallel sweeps (fixed,
// not per thread, so the order of the children's references never depends on
// the thread count).
inline constexpr size_t kKdSweepChunks = 64;

// A triangle as one node sees it: its bounds clipped to the node's voxel.
struct KdRef {
  uint32_t tri;
  Aabb bounds;
};

struct KdSplit {
  int axis = -1;  // -1: no plane found
  float position = 0.0f;
  float cost = kInfinity;  // in the units of KdBuildConfig: a leaf costs intersectionCost * N
};

// The cheapest plane strictly inside `voxel` leaving both children at least
// minThickness thick, or axis -1. Called from several threads at once.
using KdSplitFinder = KdSplit (*)(std::span<const KdRef> refs, const Aabb& voxel, const KdBuildConfig& config,
                                  float minThickness);

// The tree of `tris` with each node split at findSplit's plane while that is
// cheaper than a leaf, the node has more than minElements references and
// fewer than the effective maxDepth splits above it.
KdTree buildKdTreeWith(std::span<const Triangle> tris, const KdBuildConfig& config, KdSplitFinder findSplit);

// The bounds of the part of `tri` inside the closed box (empty when it misses).
Aabb clipTriangleToBox(const Triangle& tri, const Aabb& box);

}  // namespace passtrace
