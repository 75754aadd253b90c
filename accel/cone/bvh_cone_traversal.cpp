// Cones through a BVH: a stack traversal, nearer child first (seed 000
// section 3), or with ConeQueryConfig::sortedNodes the node-sorted one. Each child box is tested with the cone/box slab test
// (coneBox, Listing 2); children are pushed farthest first so the nearest
// is popped next. Entries that start beyond the hit list's cut-off are
// culled on pop. The Kay/Kajiya tree of "kk-bvh"; its escape sequence
// cannot serve a cone, which needs both children of a node.
#include <algorithm>
#include <chrono>

#include "accel/bvh/bvh_structures.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/cone/cone_traversal.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

class BvhConeTraversal final : public ConeTraversal {
 public:
  BvhConeTraversal(std::span<const Triangle> tris, Bvh bvh, AccelStats stats)
      : tris_(tris), bvh_(std::move(bvh)), stats_(std::move(stats)) {}

  void query(const Cone& cone, const ConeQueryConfig& config, ConeScratch&, ConeResult& result) const override {
    result.nodes = result.triangleTests = 0;
    ConeHitList list(result.hits, config);
    if (bvh_.empty()) return;
    const glm::vec3 k = coneSpread(cone);
    struct Entry {
      uint32_t node;
      float t0;
    };
    // The stack (or, sorted, a min-heap by t0); depth can exceed any fixed
    // bound for Kay/Kajiya trees.
    std::vector<Entry> stack;
    stack.reserve(64);
    const auto farther = [](const Entry& a, const Entry& b) { return a.t0 > b.t0; };
    float t0 = std::max(0.0f, config.tNear), t1 = config.tFar;
    if (coneBox(cone, k, bvh_.nodes[0].box, t0, t1)) stack.push_back({0, t0});
    Entry children[64];
    while (!stack.empty()) {
      if (config.sortedNodes) std::pop_heap(stack.begin(), stack.end(), farther);
      const Entry e = stack.back();
      stack.pop_back();
      if (e.t0 > list.cutoff()) {
        if (config.sortedNodes) break;  // every node left starts farther
        continue;
      }
      ++result.nodes;
      const BvhNode& n = bvh_.nodes[e.node];
      if (n.isLeaf()) {
        ++result.triangleTests;  // one triangle per leaf, met once
        float t;
        if (coneMeetsTriangle(cone, tris_[n.triangle], t)) list.insert({t, n.triangle});
        continue;
      }
      int count = 0;
      for (uint32_t c = 0; c < n.childCount && count < 64; ++c) {
        const uint32_t child = bvh_.children[n.firstChild + c];
        float c0 = std::max(0.0f, config.tNear), c1 = config.tFar;
        if (coneBox(cone, k, bvh_.nodes[child].box, c0, c1) && c0 <= list.cutoff()) children[count++] = {child, c0};
      }
      if (config.sortedNodes) {
        for (int c = 0; c < count; ++c) {
          stack.push_back(children[c]);
          std::push_heap(stack.begin(), stack.end(), farther);
        }
        continue;
      }
      std::sort(children, children + count, farther);
      stack.insert(stack.end(), children, children + count);
    }
    list.finish();
  }
  const AccelStats& stats() const override { return stats_; }

 private:
  std::span<const Triangle> tris_;
  Bvh bvh_;
  AccelStats stats_;
};

}  // namespace

ConeStreamTree makeKkBvhStreamCone(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildKayKajiya(tris, config.kayKajiya);
  ConeStreamTree out;
  out.kernel = "cone/bvh_cone.frag";
  out.stats = bvhStats("kk-bvh", bvh);
  std::vector<float>& d = out.data;
  out.nodeBase = 0;
  uint32_t widest = 1;
  for (const BvhNode& n : bvh.nodes) {
    d.insert(d.end(), {n.box.min.x, n.box.min.y, n.box.min.z, n.box.max.x, n.box.max.y, n.box.max.z,
                       bitsAsFloat(n.triangle), bitsAsFloat(n.firstChild), bitsAsFloat(n.childCount)});
    widest = std::max(widest, n.childCount);
  }
  out.refBase = uint32_t(d.size());
  for (uint32_t c : bvh.children) d.push_back(bitsAsFloat(c));
  out.triBase = uint32_t(d.size());
  for (const Triangle& t : tris)
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) d.insert(d.end(), {p.x, p.y, p.z});
  out.nodeCount = uint32_t(bvh.nodes.size());
  // A visit pops one entry and pushes at most `widest`: per level at most widest - 1 more.
  out.stackSize = bvh.depth() * widest + 1;
  out.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::unique_ptr<ConeTraversal> makeKkBvhCone(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh = buildKayKajiya(tris, config.kayKajiya);
  AccelStats stats = bvhStats("kk-bvh", bvh);
  stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return std::make_unique<BvhConeTraversal>(tris, std::move(bvh), std::move(stats));
}

}  // namespace passtrace
