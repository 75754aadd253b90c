#include "accel/bvh_stack/bvh_build_driver.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_invoke.h>

namespace passtrace {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

Aabb boxOf(std::span<const BvhBuildRef> refs) {
  Aabb box;
  for (const BvhBuildRef& r : refs) box.extend(r.box);
  return box;
}

int largestAxis(const glm::vec3& e) { return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2); }

struct PendingSplit {
  std::vector<BvhBuildRef> refs;
  uint32_t depth;   // level of this node, the root 1
  uint32_t parent;  // node whose slot it fills; kNoHit for the root
  int slot;
};

}  // namespace

double binaryBvhSahCost(const BinaryBvh& bvh, double traversalCost, double intersectionCost) {
  if (bvh.empty()) return 0.0;
  const double rootArea = bvh.bounds.surfaceArea();
  const auto weight = [&](const Aabb& box) { return rootArea > 0.0 ? box.surfaceArea() / rootArea : 1.0; };
  double cost = 0.0;
  // The root's own box is the scene box (weight 1) unless it is a lone leaf.
  if (!bvh.nodes[0].child[0].isLeaf() || bvh.nodes[0].child[1].present) cost += traversalCost;
  for (const BvhStackNode& node : bvh.nodes)
    for (const BvhChild& c : node.child) {
      if (!c.present) continue;
      cost += c.isLeaf() ? intersectionCost * c.count * weight(c.box) : traversalCost * weight(c.box);
    }
  return cost;
}

std::vector<BvhBuildRef> bvhBuildRefs(std::span<const Triangle> tris) {
  std::vector<BvhBuildRef> refs;
  refs.reserve(tris.size());
  for (uint32_t i = 0; i < tris.size(); ++i)
    if (finite(tris[i].v0) && finite(tris[i].v1) && finite(tris[i].v2)) refs.push_back({tris[i].bounds(), i});
  return refs;
}

Aabb bvhCentroidBox(std::span<const BvhBuildRef> refs) {
  Aabb box;
  for (const BvhBuildRef& r : refs) box.extend(r.box.center());
  return box;
}

void bvhMedianSplit(std::vector<BvhBuildRef>& refs, std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right) {
  const int axis = largestAxis(bvhCentroidBox(refs).extent());
  const auto mid = refs.begin() + std::ptrdiff_t(refs.size() / 2);
  std::nth_element(refs.begin(), mid, refs.end(), [axis](const BvhBuildRef& a, const BvhBuildRef& b) {
    const float ca = a.box.min[axis] + a.box.max[axis], cb = b.box.min[axis] + b.box.max[axis];
    return ca < cb || (ca == cb && a.triangle < b.triangle);
  });
  left.assign(refs.begin(), mid);
  right.assign(mid, refs.end());
}

namespace {

// The subtree over refs whose root is at level `depth`, with the explicit
// work stack; depth and bounds as the whole tree's would count them.
BinaryBvh buildSequential(std::vector<BvhBuildRef> refs, uint32_t depth, const BvhStackConfig& config,
                          const BvhSplitter& split) {
  BinaryBvh bvh;
  bvh.bounds = boxOf(refs);
  std::vector<PendingSplit> stack;
  stack.push_back({std::move(refs), depth, kNoHit, 0});
  while (!stack.empty()) {
    PendingSplit work = std::move(stack.back());
    stack.pop_back();
    const Aabb box = boxOf(work.refs);
    std::vector<BvhBuildRef> left, right;
    bool inner = work.refs.size() > config.leafSize && work.depth < config.maxDepth &&
                 split(work.refs, box, work.depth, left, right);
    if (inner && (left.empty() || right.empty())) bvhMedianSplit(work.refs, left, right);
    if (!inner) {
      const BvhChild leaf{box, uint32_t(bvh.references.size()), uint32_t(work.refs.size())};
      for (const BvhBuildRef& r : work.refs) bvh.references.push_back(r.triangle);
      if (work.parent == kNoHit) {
        BvhStackNode root;
        root.child[0] = leaf;
        root.child[1].present = false;
        bvh.nodes.push_back(root);
      } else {
        bvh.nodes[work.parent].child[work.slot] = leaf;
      }
      ++bvh.leaves;
      bvh.depth = std::max(bvh.depth, work.depth);
      continue;
    }
    const auto index = uint32_t(bvh.nodes.size());
    bvh.nodes.emplace_back();
    if (work.parent != kNoHit) bvh.nodes[work.parent].child[work.slot] = BvhChild{box, index, 0};
    work.refs = {};  // release before the children
    stack.push_back({std::move(right), work.depth + 1, index, 1});
    stack.push_back({std::move(left), work.depth + 1, index, 0});  // left first: depth-first order
  }
  return bvh;
}

// Hangs `sub` (a subtree's own arrays) under slot `slot` of out's node 0.
void attach(BinaryBvh& out, const BinaryBvh& sub, int slot) {
  const auto refOffset = uint32_t(out.references.size());
  out.references.insert(out.references.end(), sub.references.begin(), sub.references.end());
  out.leaves += sub.leaves;
  out.depth = std::max(out.depth, sub.depth);
  if (sub.nodes.size() == 1 && !sub.nodes[0].child[1].present) {  // a lone leaf: link it directly
    BvhChild leaf = sub.nodes[0].child[0];
    leaf.index += refOffset;
    out.nodes[0].child[slot] = leaf;
    return;
  }
  const auto nodeOffset = uint32_t(out.nodes.size());
  for (BvhStackNode node : sub.nodes) {
    for (BvhChild& c : node.child)
      if (c.present) c.index += c.isLeaf() ? refOffset : nodeOffset;
    out.nodes.push_back(node);
  }
  out.nodes[0].child[slot] = BvhChild{sub.bounds, nodeOffset, 0};
}

// Large nodes split here and their two subtrees built on all cores; the
// result depends only on the splits, not on the threads.
BinaryBvh buildParallel(std::vector<BvhBuildRef> refs, uint32_t depth, const BvhStackConfig& config,
                        const BvhSplitter& split) {
  constexpr size_t kGrain = 16384;  // below this a subtree is built by one thread
  if (refs.size() < kGrain || depth >= config.maxDepth) return buildSequential(std::move(refs), depth, config, split);
  const Aabb box = boxOf(refs);
  std::vector<BvhBuildRef> left, right;
  if (!split(refs, box, depth, left, right)) return buildSequential(std::move(refs), depth, config, split);
  if (left.empty() || right.empty()) bvhMedianSplit(refs, left, right);
  refs = {};
  BinaryBvh below[2];
  tbb::parallel_invoke([&] { below[0] = buildParallel(std::move(left), depth + 1, config, split); },
                       [&] { below[1] = buildParallel(std::move(right), depth + 1, config, split); });
  BinaryBvh out;
  out.bounds = box;
  out.nodes.emplace_back();
  attach(out, below[0], 0);
  attach(out, below[1], 1);
  return out;
}

}  // namespace

BinaryBvh buildBinaryBvh(std::span<const Triangle> tris, const BvhStackConfig& config, const BvhSplitter& split,
                         bool threadSafeSplitter) {
  std::vector<BvhBuildRef> all = bvhBuildRefs(tris);
  if (all.empty()) return {};
  return threadSafeSplitter ? buildParallel(std::move(all), 1, config, split)
                            : buildSequential(std::move(all), 1, config, split);
}

}  // namespace passtrace
