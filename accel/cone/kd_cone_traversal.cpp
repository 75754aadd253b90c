// Cones through a kd-tree: the stack traversal of seed 000 Listing 1. The
// cone's interval [t0, t1] along the axis is cut at each split into the
// part below and the part above the plane (coneSide, Eq. 2); the nearer
// non-empty child is entered, the other pushed with its own interval.
// Nodes that start beyond the hit list's cut-off are culled (Listing 1's
// "max(t1, tmin) <= t_n"), on push and on pop.
#include <chrono>

#include "accel/cone/cone_traversal.h"
#include "accel/kd/kd_structures.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

class KdConeTraversal final : public ConeTraversal {
 public:
  KdConeTraversal(std::span<const Triangle> tris, KdTree tree, AccelStats stats)
      : tris_(tris), tree_(std::move(tree)), stats_(std::move(stats)) {}

  void query(const Cone& cone, const ConeQueryConfig& config, ConeScratch& scratch, ConeResult& result) const override {
    result.nodes = result.triangleTests = 0;
    ConeHitList list(result.hits, config);
    if (tree_.empty()) return;
    scratch.begin(tris_.size());
    const glm::vec3 k = coneSpread(cone);
    float t0 = std::max(0.0f, config.tNear), t1 = config.tFar;
    if (!coneBox(cone, k, tree_.bounds, t0, t1)) return;
    struct Entry {
      uint32_t node;
      float t0, t1;
    };
    Entry stack[2 * kKdDepthLimit + 2];  // one push per level
    int top = 0;
    uint32_t node = 0;
    while (true) {
      ++result.nodes;
      const KdNode& n = tree_.nodes[node];
      bool next = false;
      if (!n.isLeaf()) {
        float l0 = t0, l1 = t1, r0 = t0, r1 = t1;
        const float cut = list.cutoff();
        const bool left = coneSide(cone, k, int(n.axis), n.split, 0, l0, l1) && l0 <= cut;
        const bool right = coneSide(cone, k, int(n.axis), n.split, 1, r0, r1) && r0 <= cut;
        if (left && right) {
          const bool leftFirst = l0 <= r0;
          stack[top++] = leftFirst ? Entry{n.rightChild, r0, r1} : Entry{node + 1, l0, l1};
          node = leftFirst ? node + 1 : n.rightChild;
          t0 = leftFirst ? l0 : r0, t1 = leftFirst ? l1 : r1;
          next = true;
        } else if (left || right) {
          node = left ? node + 1 : n.rightChild;
          t0 = left ? l0 : r0, t1 = left ? l1 : r1;
          next = true;
        }
      } else {
        for (uint32_t r = 0; r < n.refCount; ++r) {
          const uint32_t id = tree_.references[n.firstRef + r];
          ++result.triangleTests;
          float t;
          if (scratch.firstVisit(id) && coneMeetsTriangle(cone, tris_[id], t)) list.insert({t, id});
        }
      }
      if (next) continue;
      // Pop until an entry that can still hold a nearer hit.
      bool found = false;
      while (top > 0 && !found) {
        const Entry e = stack[--top];
        if (e.t0 <= list.cutoff()) node = e.node, t0 = e.t0, t1 = e.t1, found = true;
      }
      if (!found) break;
    }
    list.finish();
  }
  const AccelStats& stats() const override { return stats_; }

 private:
  std::span<const Triangle> tris_;
  KdTree tree_;
  AccelStats stats_;
};

using KdBuild = KdTree (*)(std::span<const Triangle>, const AccelBuildConfig&);

std::unique_ptr<ConeTraversal> make(const char* name, std::span<const Triangle> tris, KdBuild build,
                                    const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  KdTree tree = build(tris, config);
  AccelStats stats;
  stats.name = name;
  setKdTreeStats(stats, tree);
  stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return std::make_unique<KdConeTraversal>(tris, std::move(tree), std::move(stats));
}

KdTree pbrtTree(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return buildKdTreePbrt(tris, kdPbrtConfigFor(config));
}

}  // namespace

ConeStreamTree makeKdTreeStreamCone(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const KdTree tree = buildKdTreeFor(tris, config);
  ConeStreamTree out;
  out.kernel = "cone/kd_cone.frag";
  out.stats.name = "kd-tree";
  setKdTreeStats(out.stats, tree);
  std::vector<float>& d = out.data;
  for (int a = 0; a < 3; ++a) d.push_back(tree.bounds.min[a]);
  for (int a = 0; a < 3; ++a) d.push_back(tree.bounds.max[a]);
  out.nodeBase = uint32_t(d.size());
  for (const KdNode& n : tree.nodes) d.insert(d.end(), {n.split, bitsAsFloat(n.axis), bitsAsFloat(n.rightChild), bitsAsFloat(n.firstRef),
                                                         bitsAsFloat(n.refCount)});
  out.refBase = uint32_t(d.size());
  for (uint32_t r : tree.references) d.push_back(bitsAsFloat(r));
  out.triBase = uint32_t(d.size());
  for (const Triangle& t : tris)
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) d.insert(d.end(), {p.x, p.y, p.z});
  out.nodeCount = uint32_t(tree.nodes.size());
  out.stackSize = tree.depth() + 1;  // at most one push per level
  out.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::unique_ptr<ConeTraversal> makeKdTreeCone(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return make("kd-tree", tris, buildKdTreeFor, config);
}

std::unique_ptr<ConeTraversal> makeKdPbrtCone(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return make("kd-pbrt", tris, pbrtTree, config);
}

}  // namespace passtrace
