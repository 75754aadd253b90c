#include "accel/wide_bvh/sbvh_binary_bvh.h"

#include <algorithm>
#include <vector>

#include "accel/bvh_stack/sbvh_builder.h"

namespace passtrace {

BvhStackConfig wideSbvhConfig(const SahBuildConfig& sah) {
  BvhStackConfig config;
  config.leafSize = sah.leafSize;
  config.maxLeafSize = sah.maxLeafSize;
  config.bins = uint32_t(sah.bins);
  config.traversalCost = sah.traversalCost;
  config.intersectionCost = sah.intersectionCost;
  return config;
}

SahBinaryBvh toSahBinaryBvh(const BinaryBvh& sbvh, uint32_t maxLeafSize) {
  SahBinaryBvh out;
  if (sbvh.empty()) return out;
  out.prims = sbvh.references;
  // A node of `out` still to fill from a source child: an inner node of the
  // SBVH, or a range of references (a leaf, or half of an oversized one).
  struct Pending {
    uint32_t target;  // index in out.nodes, already holding its box
    BvhChild source;
  };
  const uint32_t cap = std::max(1u, maxLeafSize);
  std::vector<Pending> stack;
  const BvhStackNode& root = sbvh.nodes[0];
  if (!root.child[1].present) {  // a lone leaf
    out.nodes.push_back({root.child[0].box, 0, 0});
    stack.push_back({0, root.child[0]});
  } else {
    Aabb box = root.child[0].box;
    box.extend(root.child[1].box);
    out.nodes.push_back({box, 0, 0});
    stack.push_back({0, BvhChild{box, 0, 0}});
  }
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const BvhChild& c = p.source;
    if (c.isLeaf() && c.count <= cap) {
      out.nodes[p.target].first = c.index;
      out.nodes[p.target].count = c.count;
      continue;
    }
    BvhChild halves[2];
    if (c.isLeaf()) {  // oversized: two halves, each bounded by the leaf's box
      halves[0] = BvhChild{c.box, c.index, c.count / 2};
      halves[1] = BvhChild{c.box, c.index + c.count / 2, c.count - c.count / 2};
    } else {
      halves[0] = sbvh.nodes[c.index].child[0];
      halves[1] = sbvh.nodes[c.index].child[1];
    }
    const auto pair = uint32_t(out.nodes.size());
    out.nodes[p.target].first = pair;
    out.nodes[p.target].count = 0;
    for (int k = 0; k < 2; ++k) {
      out.nodes.push_back({halves[k].box, 0, 0});
      stack.push_back({pair + uint32_t(k), halves[k]});
    }
  }
  return out;
}

SahBinaryBvh buildSbvhBinaryBvh(std::span<const Triangle> tris, const SahBuildConfig& sah) {
  return toSahBinaryBvh(buildSbvh(tris, wideSbvhConfig(sah)), sah.maxLeafSize);
}

}  // namespace passtrace
