#pragma once
// A binary BVH in the Aila–Laine layout (Aila & Laine 2009): each node holds
// its two children's boxes and links, so one visit tests both boxes and
// picks the nearer child. Leaves are ranges of the reference array (an SBVH
// may reference a triangle from several leaves). Every builder
// (sah_builder.h, sbvh_builder.h, middle_builder.h) returns this type.

#include <cstdint>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

// Build constants shared by the three builders.
struct BvhStackConfig {
  uint32_t leafSize = 4;        // a node of this many references or fewer is always a leaf
  uint32_t maxLeafSize = 16;    // SAH/SBVH: above this a node always splits, at or below it the SAH decides
  uint32_t maxDepth = 64;       // levels; deeper nodes become leaves (bounds the traversal stack)
  uint32_t bins = 32;           // binned SAH and SBVH spatial bins per axis
  float traversalCost = 1.0f;   // SAH K_T, as the kd builders (kd_sah_cost.h)
  float intersectionCost = 1.5f;  // SAH K_I
  // SBVH: spatial splits are tried only where the object split's children
  // overlap by more than alpha times the root's area (Stich et al. 2009: 1e-5).
  float sbvhAlpha = 1e-5f;
  // SBVH: references may grow to (1 + budget) times the triangles.
  float sbvhSplitBudget = 1.0f;
};

// One child slot of a node: its box, and what it links to.
struct BvhChild {
  Aabb box;
  uint32_t index = 0;  // count == 0: node index; count > 0: first entry in BinaryBvh::references
  uint32_t count = 0;  // references of a leaf; 0 = an internal node
  bool present = true; // false only for the second slot of a root that is a single leaf
  bool isLeaf() const { return count > 0; }
};

struct BvhStackNode {
  BvhChild child[2];
};

struct BinaryBvh {
  std::vector<BvhStackNode> nodes;   // nodes[0] is the root; empty for an empty scene
  std::vector<uint32_t> references;  // triangle indices, leaf by leaf
  Aabb bounds;                       // the scene box
  uint32_t depth = 0;                // levels, a lone leaf 1 (then nodes holds one node of one leaf)
  size_t leaves = 0;

  bool empty() const { return nodes.empty(); }
};

// Expected cost of a ray through the root box (kd_sah_cost.h's formula):
// sum of K_T SA(node) over internal nodes + K_I n SA(leaf) over leaves,
// over SA(root). A lone leaf root counts as a leaf.
double binaryBvhSahCost(const BinaryBvh& bvh, double traversalCost, double intersectionCost);

}  // namespace passtrace
