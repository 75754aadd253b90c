#pragma once
// The binary SAH BVH that the wide BVH (wide_bvh.h) is collapsed from, and its
// two builders: a binned one on all cores (the fast one, tbb tasks; the
// thread count is --threads through tbb::global_control) and an exact
// full-sweep one (every centroid position on every axis: the reference the
// binned builder's SAH cost is measured against).

#include <cstdint>
#include <span>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

// Named apart from bvh_stack's BinaryBvh (accel/bvh_stack/binary_bvh.h, the
// Aila–Laine layout): both link into the same binaries, so one name for two
// types would break the one-definition rule.
// A leaf when count > 0 (prims[first, first + count)); otherwise its children
// are nodes[first] and nodes[first + 1].
struct SahBinaryBvhNode {
  Aabb bounds;
  uint32_t first = 0;
  uint32_t count = 0;
  bool leaf() const { return count > 0; }
};

struct SahBinaryBvh {
  std::vector<SahBinaryBvhNode> nodes;  // nodes[0] is the root; empty for no triangles
  std::vector<uint32_t> prims;          // triangle indices, leaf by leaf
};

struct SahBuildConfig {
  int bins = 32;                // binned builder: bins per axis, 2-32 (all three axes are binned)
  // Nodes of at most this many triangles are leaves without a split search:
  // the wide BVH tests a pack of 4 at the cost of one, and the collapse merges
  // such subtrees into one pack anyway. Both builders apply it.
  uint32_t leafSize = 4;
  uint32_t maxLeafSize = 8;     // larger nodes are always split (two packs of 4 in the wide BVH)
  float traversalCost = 1.0f;   // K_T, as the kd builders' (kd_sah_cost.h)
  float intersectionCost = 1.5f;  // K_I
  uint32_t parallelGrain = 4096;  // nodes with more triangles split into parallel tasks
};

SahBinaryBvh buildBinnedSahBvh(std::span<const Triangle> tris, const SahBuildConfig& config = {});
// Sorts every node's triangles by centroid on each axis and tries every split.
SahBinaryBvh buildExactSahBvh(std::span<const Triangle> tris, const SahBuildConfig& config = {});

// Expected cost of a ray that hits the root box (Haines/MacDonald & Booth):
// sum of K_T SA(inner) / SA(root) plus K_I n SA(leaf) / SA(root); 0 when empty.
double bvhSahCost(const SahBinaryBvh& bvh, const SahBuildConfig& config = {});
// Levels of the tree (a single leaf is 1).
uint32_t bvhDepth(const SahBinaryBvh& bvh);

}  // namespace passtrace
