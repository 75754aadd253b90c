#include <algorithm>

#include "accel/wide_bvh/wide_bvh.h"

namespace passtrace {
namespace {

WideBvhNode emptyNode() {
  WideBvhNode node;
  for (int i = 0; i < kWideBvhWidth; ++i) {
    node.minX[i] = node.maxX[i] = node.minY[i] = node.maxY[i] = node.minZ[i] = node.maxZ[i] = kInfinity;
    node.child[i] = kWideEmpty;
  }
  return node;
}

class Collapser {
public:
  Collapser(const SahBinaryBvh& bvh, std::span<const Triangle> tris, const WideBvhConfig& config, WideBvh& out)
      : bvh_(bvh), tris_(tris), config_(config), out_(out) {
    counts_.resize(bvh.nodes.size());
    out.nodes.reserve(bvh.nodes.size() / 4 + 1);
    out.packs.reserve(bvh.prims.size() / 2 + 1);
    // Children come after their parent, so a reverse sweep sums subtrees first.
    for (size_t i = bvh.nodes.size(); i-- > 0;) {
      const SahBinaryBvhNode& n = bvh.nodes[i];
      counts_[i] = n.leaf() ? n.count : counts_[n.first] + counts_[n.first + 1];
    }
  }

  // Returns the reference to the subtree rooted at binary node `b`.
  uint32_t subtree(uint32_t b, uint32_t level) {
    out_.depth = std::max(out_.depth, level);
    if (isLeaf(b)) return leaf(b);
    const uint32_t index = uint32_t(out_.nodes.size());
    out_.nodes.emplace_back();
    uint32_t children[kWideBvhWidth] = {bvh_.nodes[b].first, bvh_.nodes[b].first + 1};
    size_t count = 2;
    while (count < size_t(kWideBvhWidth)) {
      int open = -1;
      float largest = -1.0f;
      for (size_t i = 0; i < count; ++i) {
        if (isLeaf(children[i])) continue;
        const float area = bvh_.nodes[children[i]].bounds.surfaceArea();
        if (area > largest) largest = area, open = int(i);
      }
      if (open < 0) break;
      const uint32_t c = children[size_t(open)];
      children[size_t(open)] = bvh_.nodes[c].first;
      children[count++] = bvh_.nodes[c].first + 1;
    }
    WideBvhNode node = emptyNode();
    for (size_t i = 0; i < count; ++i) {
      const Aabb& box = bvh_.nodes[children[i]].bounds;
      node.minX[i] = box.min.x, node.minY[i] = box.min.y, node.minZ[i] = box.min.z;
      node.maxX[i] = box.max.x, node.maxY[i] = box.max.y, node.maxZ[i] = box.max.z;
      node.child[i] = subtree(children[i], level + 1);
    }
    out_.nodes[index] = node;
    return index;
  }

private:
  bool isLeaf(uint32_t b) const { return bvh_.nodes[b].leaf() || counts_[b] <= config_.mergeLeafTriangles; }

  void gather(uint32_t b, std::vector<uint32_t>& prims) const {
    const SahBinaryBvhNode& n = bvh_.nodes[b];
    if (n.leaf()) {
      prims.insert(prims.end(), bvh_.prims.begin() + n.first, bvh_.prims.begin() + n.first + n.count);
    } else {
      gather(n.first, prims);
      gather(n.first + 1, prims);
    }
  }

  uint32_t leaf(uint32_t b) {
    std::vector<uint32_t>& prims = scratch_;  // reused: one leaf at a time
    prims.clear();
    gather(b, prims);
    // An SBVH's merged subtrees may reference a triangle more than once: test it once.
    auto kept = prims.begin();
    for (const uint32_t id : prims)
      if (std::find(prims.begin(), kept, id) == kept) *kept++ = id;
    prims.erase(kept, prims.end());
    const uint32_t first = uint32_t(out_.packs.size());
    const uint32_t packs = uint32_t((prims.size() + kTrianglePackWidth - 1) / kTrianglePackWidth);
    for (uint32_t p = 0; p < packs; ++p) {
      TrianglePack pack{};
      for (int l = 0; l < kTrianglePackWidth; ++l) {
        const size_t i = size_t(p) * kTrianglePackWidth + size_t(l);
        pack.id[l] = kNoHit;
        if (i >= prims.size()) continue;
        const Triangle& t = tris_[prims[i]];
        const glm::vec3 e1 = t.v1 - t.v0, e2 = t.v2 - t.v0;  // as intersectTriangle computes them
        pack.v0x[l] = t.v0.x, pack.v0y[l] = t.v0.y, pack.v0z[l] = t.v0.z;
        pack.e1x[l] = e1.x, pack.e1y[l] = e1.y, pack.e1z[l] = e1.z;
        pack.e2x[l] = e2.x, pack.e2y[l] = e2.y, pack.e2z[l] = e2.z;
        pack.id[l] = prims[i];
      }
      out_.packs.push_back(pack);
    }
    ++out_.leaves;
    out_.references += uint32_t(prims.size());
    return kWideLeafBit | ((packs - 1) << 29) | first;
  }

  const SahBinaryBvh& bvh_;
  std::span<const Triangle> tris_;
  const WideBvhConfig& config_;
  WideBvh& out_;
  std::vector<uint32_t> counts_;
  std::vector<uint32_t> scratch_;
};

}  // namespace

WideBvh collapseToWideBvh(const SahBinaryBvh& bvh, std::span<const Triangle> tris, const WideBvhConfig& config) {
  WideBvh out;
  if (bvh.nodes.empty()) return out;
  Collapser collapser(bvh, tris, config, out);
  if (bvh.nodes[0].leaf() || bvh.prims.size() <= config.mergeLeafTriangles) {
    // A root that is a leaf still gets an inner node, so traversal always starts at nodes[0].
    WideBvhNode node = emptyNode();
    out.nodes.push_back(node);
    const Aabb& box = bvh.nodes[0].bounds;
    node.minX[0] = box.min.x, node.minY[0] = box.min.y, node.minZ[0] = box.min.z;
    node.maxX[0] = box.max.x, node.maxY[0] = box.max.y, node.maxZ[0] = box.max.z;
    out.depth = 1;
    node.child[0] = collapser.subtree(0, 2);
    out.nodes[0] = node;
    return out;
  }
  collapser.subtree(0, 1);
  return out;
}

}  // namespace passtrace
