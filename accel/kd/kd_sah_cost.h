#pragma once
// The SAH cost of a built kd-tree: the expected cost of tracing a ray that
// hits the root voxel, if rays are uniformly distributed (Haines, MacDonald
// & Booth): the chance a ray through the root enters a node is SA(node) /
// SA(root), so
//   cost = sum over internal nodes of K_T SA(node) / SA(root)
//        + sum over leaves of K_I n(leaf) SA(leaf) / SA(root).
// With the builders' constants (K_T = traversalCost 1, K_I = intersectionCost
// 1.5) a single leaf of N triangles costs 1.5 N. A root of zero area (all
// triangles on one line or point) weighs every node 1. An empty tree costs 0.

#include "accel/kd/kd_tree.h"

namespace passtrace {

double kdSahCost(const KdTree& tree, double traversalCost, double intersectionCost);

}  // namespace passtrace
