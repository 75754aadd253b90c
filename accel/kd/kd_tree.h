#pragma once
// A kd-tree over triangles (thesis section 8): internal nodes split their
// voxel by an axis-perpendicular plane, leaves list the triangles that touch
// their voxel. Both builders (kd_tree_builder.h: SAH with split clipping;
// kd_tree_pbrt_builder.h: built the pbrt way) produce this one form, which
// the CPU traversal (kd_traversal.h) walks and kd_texels.h flattens for the
// GPU's restart and backtrack kernels.
//
// Layout is depth-first: a node's left child (below the split) is the next
// node, so only the right child's index is stored (thesis section 8.5).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

struct KdNode {
  float split = 0.0f;         // internal: plane position along `axis`
  uint32_t axis = 3;          // 0, 1, 2 = x, y, z split; 3 = leaf
  uint32_t rightChild = 0;    // internal: index of the right child (above the split); left is index + 1
  uint32_t parent = kNoHit;   // kNoHit for the root
  uint32_t firstRef = 0;      // leaf: range [firstRef, firstRef + refCount) in KdTree::references
  uint32_t refCount = 0;
  Aabb box;                   // the node's voxel; children split it at `split`
  bool isLeaf() const { return axis == 3; }
};

struct KdTree {
  Aabb bounds;                       // the root voxel: the triangles' bounds (flat dimensions stay flat)
  std::vector<KdNode> nodes;         // nodes[0] is the root; empty for an empty scene
  std::vector<uint32_t> references;  // triangle indices, leaf by leaf

  bool empty() const { return nodes.empty(); }

  // Levels on the longest root-to-leaf path: a single leaf is 1, an empty
  // tree 0. Parents precede children in the layout, so one forward pass.
  uint32_t depth() const {
    std::vector<uint32_t> level(nodes.size(), 1);
    uint32_t deepest = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (nodes[i].parent != kNoHit) level[i] = level[nodes[i].parent] + 1;
      deepest = std::max(deepest, level[i]);
    }
    return deepest;
  }

  size_t leafCount() const {
    size_t count = 0;
    for (const KdNode& node : nodes) count += node.isLeaf() ? 1 : 0;
    return count;
  }
};

// Both builders stop splitting at this many levels below the root whatever
// maxDepth asks for, so traversal stacks can be fixed-size arrays.
inline constexpr int kKdDepthLimit = 64;

}  // namespace passtrace
