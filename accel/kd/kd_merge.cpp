#include "accel/kd/kd_merge.h"

#include <algorithm>
#include <optional>
#include <vector>

namespace passtrace {
namespace {

struct Plane {
  uint32_t axis;
  float split;
};

// Closed boxes: touching counts, since triangles may lie in a voxel's face.
bool touches(const Aabb& a, const Aabb& b) {
  for (int i = 0; i < 3; ++i)
    if (a.max[i] < b.min[i] || b.max[i] < a.min[i]) return false;
  return true;
}

Aabb triangleBounds(const Triangle& t) {
  Aabb b;
  b.extend(t.v0);
  b.extend(t.v1);
  b.extend(t.v2);
  return b;
}

// A face of `bounds` that cuts `region` strictly, with the empty side outside.
std::optional<Plane> boundingCut(const Aabb& region, const Aabb& bounds) {
  for (uint32_t a = 0; a < 3; ++a) {
    if (bounds.min[a] > region.min[a] && bounds.min[a] < region.max[a]) return Plane{a, bounds.min[a]};
    if (bounds.max[a] > region.min[a] && bounds.max[a] < region.max[a]) return Plane{a, bounds.max[a]};
  }
  return std::nullopt;
}

class Merger {
 public:
  Merger(const KdTree& s, const KdTree& d, std::span<const Triangle> tris, KdTree& out)
      : s_(s), d_(d), tris_(tris), out_(out) {}

  uint32_t emit(const Aabb& region, uint32_t s, uint32_t d, uint32_t parent, int level) {
    s = descend(s_, s, region);
    d = descend(d_, d, region);
    const uint32_t index = uint32_t(out_.nodes.size());
    KdNode node;
    node.parent = parent;
    node.box = region;
    out_.nodes.push_back(node);

    std::optional<Plane> plane;
    uint32_t sLeft = s, sRight = s, dLeft = d, dRight = d;
    // The static tree's planes first, down to its leaves; then, inside a
    // static leaf, the dynamic tree's bounds and planes.
    if (level + 1 < kKdDepthLimit) {
      if (s != kNoHit) plane = boundingCut(region, s_.bounds);  // the root, where the dynamic tree sticks out
      if (!plane && s != kNoHit && !s_.nodes[s].isLeaf()) {
        plane = Plane{s_.nodes[s].axis, s_.nodes[s].split};
        sLeft = s + 1, sRight = s_.nodes[s].rightChild;
      }
      if (!plane && d != kNoHit) plane = boundingCut(region, d_.bounds);
      if (!plane && d != kNoHit && !d_.nodes[d].isLeaf()) {
        plane = Plane{d_.nodes[d].axis, d_.nodes[d].split};
        dLeft = d + 1, dRight = d_.nodes[d].rightChild;
      }
    }
    if (!plane) {
      leaf(index, region, s, d);
      return index;
    }
    Aabb below = region, above = region;
    below.max[plane->axis] = plane->split;
    above.min[plane->axis] = plane->split;
    out_.nodes[index].axis = plane->axis;
    out_.nodes[index].split = plane->split;
    emit(below, sLeft, dLeft, index, level + 1);
    const uint32_t right = emit(above, sRight, dRight, index, level + 1);
    out_.nodes[index].rightChild = right;
    return index;
  }

 private:
  // The node of `tree` below `node` that covers all of `region`: children
  // whose plane does not cut the region are skipped. kNoHit where the tree
  // has no triangles there.
  static uint32_t descend(const KdTree& tree, uint32_t node, const Aabb& region) {
    if (node == kNoHit || !touches(region, tree.bounds)) return kNoHit;
    for (;;) {
      const KdNode& n = tree.nodes[node];
      if (n.isLeaf()) return node;
      if (n.split <= region.min[n.axis]) node = n.rightChild;
      else if (n.split >= region.max[n.axis]) node = node + 1;
      else return node;
    }
  }

  // Every reference in the leaves below `node` (a leaf at the depth limit).
  static void collect(const KdTree& tree, uint32_t node, std::vector<uint32_t>& refs) {
    if (node == kNoHit) return;
    const KdNode& n = tree.nodes[node];
    if (!n.isLeaf()) {
      collect(tree, node + 1, refs);
      collect(tree, n.rightChild, refs);
      return;
    }
    refs.insert(refs.end(), tree.references.begin() + n.firstRef, tree.references.begin() + n.firstRef + n.refCount);
  }

  void leaf(uint32_t index, const Aabb& region, uint32_t s, uint32_t d) {
    refs_.clear();
    collect(s_, s, refs_);
    collect(d_, d, refs_);
    const bool subtree = (s != kNoHit && !s_.nodes[s].isLeaf()) || (d != kNoHit && !d_.nodes[d].isLeaf());
    if (subtree) {
      std::sort(refs_.begin(), refs_.end());  // below the depth limit, subtrees repeat references
      refs_.erase(std::unique(refs_.begin(), refs_.end()), refs_.end());
    }
    KdNode& n = out_.nodes[index];
    n.firstRef = uint32_t(out_.references.size());
    for (uint32_t id : refs_)
      if (touches(triangleBounds(tris_[id]), region)) out_.references.push_back(id);
    n.refCount = uint32_t(out_.references.size()) - n.firstRef;
  }

  const KdTree& s_;
  const KdTree& d_;
  std::span<const Triangle> tris_;
  KdTree& out_;
  std::vector<uint32_t> refs_;
};

}  // namespace

KdTree mergeKdTrees(const KdTree& staticTree, const KdTree& dynamicTree, std::span<const Triangle> tris) {
  KdTree merged;
  if (staticTree.empty() && dynamicTree.empty()) return merged;
  merged.bounds = staticTree.bounds;
  merged.bounds.extend(dynamicTree.bounds);
  merged.nodes.reserve(staticTree.nodes.size() + 2 * dynamicTree.nodes.size());
  merged.references.reserve(staticTree.references.size() + 2 * dynamicTree.references.size());
  Merger(staticTree, dynamicTree, tris, merged)
      .emit(merged.bounds, staticTree.empty() ? kNoHit : 0, dynamicTree.empty() ? kNoHit : 0, kNoHit, 0);
  return merged;
}

}  // namespace passtrace
