#pragma once
// The bounding interval hierarchy (Wächter & Keller 2006): a binary tree whose
// inner nodes hold one axis and two clip planes, the left child's maximum and
// the right child's minimum along that axis. Unlike a kd-tree's voxels the
// children may overlap or leave a gap, so a ray can miss both; every triangle
// is referenced exactly once.
//
// Built by global-box splitting (buildBih): the candidate plane halves the
// node's *global* box (the cell of a regular subdivision of the scene box), not
// the box of its triangles; triangles go left or right by their centroid's
// side; when one side would be empty the global box shrinks to the other half
// and splitting continues without a node, as the paper does.

#include <cstdint>
#include <span>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

struct BihConfig {
  int leafSize = 4;         // at most this many triangles make a leaf
  int maxDepth = 64;        // levels; a node at this depth is a leaf whatever its size
  int maxEmptySplits = 64;  // global-box halvings in a row without a node before giving up (a leaf)
};

struct BihNode {
  static constexpr uint32_t kLeaf = 3;
  uint32_t axis = kLeaf;  // 0, 1, 2 for inner nodes
  float clip[2] = {0, 0};  // inner: left child's max, right child's min along axis
  uint32_t rightChild = 0;  // inner: the left child is the next node
  uint32_t firstRef = 0, refCount = 0;  // leaf: its slice of Bih::references
  bool isLeaf() const { return axis == kLeaf; }
};

struct Bih {
  std::vector<BihNode> nodes;  // depth first, root at 0; empty for no triangles
  std::vector<uint32_t> references;
  Aabb bounds;  // of every triangle
  uint32_t depth = 0;  // levels; a single leaf is 1
  size_t leafCount() const;
};

Bih buildBih(std::span<const Triangle> tris, const BihConfig& config = {});

}  // namespace passtrace
