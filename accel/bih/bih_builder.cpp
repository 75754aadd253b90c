#include <algorithm>
#include <numeric>

#include "accel/bih/bih.h"

namespace passtrace {

size_t Bih::leafCount() const {
  return size_t(std::count_if(nodes.begin(), nodes.end(), [](const BihNode& n) { return n.isLeaf(); }));
}

namespace {

class BihBuilder {
 public:
  BihBuilder(std::span<const Triangle> tris, const BihConfig& config, Bih& out) : config_(config), out_(out) {
    boxes_.reserve(tris.size());
    centroids_.reserve(tris.size());
    for (const Triangle& t : tris) {
      boxes_.push_back(t.bounds());
      centroids_.push_back(boxes_.back().center());
      out_.bounds.extend(boxes_.back());
    }
    out_.references.resize(tris.size());
    std::iota(out_.references.begin(), out_.references.end(), 0u);
  }

  void build() {
    if (out_.references.empty()) return;
    node(0, uint32_t(out_.references.size()), out_.bounds, 1);
  }

 private:
  // Builds the node over references [begin, end) inside global box `cell`, at
  // `depth` (the root is 1). Recursion depth is bounded by maxDepth.
  void node(uint32_t begin, uint32_t end, Aabb cell, uint32_t depth) {
    out_.depth = std::max(out_.depth, depth);
    const uint32_t index = uint32_t(out_.nodes.size());
    out_.nodes.emplace_back();
    const bool small = end - begin <= uint32_t(std::max(config_.leafSize, 1)) || int(depth) >= config_.maxDepth;
    for (int empty = 0; !small && empty <= config_.maxEmptySplits; ++empty) {
      const glm::vec3 e = cell.extent();
      const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
      const float plane = 0.5f * (cell.min[axis] + cell.max[axis]);
      if (!(plane > cell.min[axis] && plane < cell.max[axis])) break;  // the cell cannot be halved further
      uint32_t* refs = out_.references.data();
      uint32_t* mid = std::partition(refs + begin, refs + end,
                                     [&](uint32_t t) { return centroids_[t][axis] < plane; });
      const uint32_t split = uint32_t(mid - refs);
      if (split == begin) {  // nothing left of the plane: continue in the right half
        cell.min[axis] = plane;
        continue;
      }
      if (split == end) {  // nothing right of it: continue in the left half
        cell.max[axis] = plane;
        continue;
      }
      float leftMax = -kInfinity, rightMin = kInfinity;
      for (uint32_t i = begin; i < split; ++i) leftMax = std::max(leftMax, boxes_[refs[i]].max[axis]);
      for (uint32_t i = split; i < end; ++i) rightMin = std::min(rightMin, boxes_[refs[i]].min[axis]);
      Aabb leftCell = cell, rightCell = cell;
      leftCell.max[axis] = plane;
      rightCell.min[axis] = plane;
      node(begin, split, leftCell, depth + 1);
      const uint32_t right = uint32_t(out_.nodes.size());
      node(split, end, rightCell, depth + 1);
      BihNode& n = out_.nodes[index];
      n.axis = uint32_t(axis);
      n.clip[0] = leftMax;
      n.clip[1] = rightMin;
      n.rightChild = right;
      return;
    }
    BihNode& leaf = out_.nodes[index];
    leaf.firstRef = begin;
    leaf.refCount = end - begin;
  }

  const BihConfig& config_;
  Bih& out_;
  std::vector<Aabb> boxes_;
  std::vector<glm::vec3> centroids_;
};

}  // namespace

Bih buildBih(std::span<const Triangle> tris, const BihConfig& config) {
  Bih bih;
  BihBuilder(tris, config, bih).build();
  return bih;
}

}  // namespace passtrace
