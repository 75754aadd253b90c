#pragma once
// A bounding volume hierarchy over triangles (thesis section 9), one triangle
// per leaf. Nodes may have any number of children: Kay/Kajiya builds binary
// trees, Goldsmith/Salmon n-ary ones, and every consumer (flattening,
// recursive traversal, statistics) treats both alike.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "accel/geometry/geometry.h"

namespace passtrace {

struct BvhNode {
  Aabb box;                   // encloses every triangle below (a leaf: its triangle)
  uint32_t triangle = kNoHit; // leaf: index of the triangle in the scene
  uint32_t firstChild = 0;    // internal: first entry in Bvh::children
  uint32_t childCount = 0;    // internal: entries, in traversal order
  bool isLeaf() const { return childCount == 0; }
};

struct Bvh {
  std::vector<BvhNode> nodes;      // nodes[0] is the root; empty for an empty scene
  std::vector<uint32_t> children;  // node indices, grouped per parent

  bool empty() const { return nodes.empty(); }

  // Levels on the longest root-to-leaf path: a single leaf is depth 1, an
  // empty tree 0. Walks with an explicit stack: trees may be deep.
  uint32_t depth() const {
    if (nodes.empty()) return 0;
    uint32_t deepest = 0;
    std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 1u}};  // (node, its level)
    while (!stack.empty()) {
      const auto [index, level] = stack.back();
      stack.pop_back();
      const BvhNode& node = nodes[index];
      if (node.isLeaf()) {
        deepest = std::max(deepest, level);
        continue;
      }
      for (uint32_t c = 0; c < node.childCount; ++c)
        stack.emplace_back(children[node.firstChild + c], level + 1);
    }
    return deepest;
  }

  size_t leafCount() const {
    size_t count = 0;
    for (const BvhNode& node : nodes) count += node.isLeaf() ? 1 : 0;
    return count;
  }
  size_t internalCount() const { return nodes.size() - leafCount(); }
};

}  // namespace passtrace
