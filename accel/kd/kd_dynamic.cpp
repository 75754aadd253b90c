#include "accel/kd/kd_dynamic.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "accel/kd/kd_merge.h"
#include "accel/kd/kd_structures.h"
#include "accel/kd/kd_traversal.h"
#include "accel/milliseconds_since.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {


// One tree traced as its row does on the CPU.
class TreeTracer {
 public:
  TreeTracer(const KdTree& tree, std::optional<KdStreamVariant> variant, std::span<const Triangle> tris,
             std::span<const glm::vec4> triangleTexels, TriangleTest test, int shortStackSize)
      : tree_(tree), tris_(tris), test_(test) {
    if (variant) {
      flat_ = flattenKdStream(*variant, tree, tris.size(), shortStackSize);
      data_ = KdStreamData{*variant,      flat_->sceneBox, flat_->texels.nodes, flat_->texels.lists,
                           triangleTexels, test,           flat_->stackSize};
      stats_ = flat_->stats;
    } else {
      stats_.floatsPerTriangle = kdFloatsPerTriangle(tree, tris.size(), kKdRestartStride);
      stats_.nodes = tree.nodes.size();
      stats_.leaves = tree.leafCount();
      stats_.references = tree.references.size();
      stats_.depth = tree.depth();
    }
  }
  Hit trace(const Ray& ray, bool anyHit, RayStats* stats) const {
    if (flat_) return traverseKdStream(data_, ray, anyHit, stats);
    return traverseKdTree(tree_, tris_, ray, anyHit, stats, test_);
  }
  const AccelStats& stats() const { return stats_; }

 private:
  const KdTree& tree_;
  std::span<const Triangle> tris_;
  TriangleTest test_;
  std::optional<KdStreamBuild> flat_;
  KdStreamData data_;
  AccelStats stats_;
};

// One tree (merge) or two (two-trees, static first).
class DynamicAccelerator final : public CpuAccelerator {
 public:
  DynamicAccelerator(const KdDynamicTrees& trees, std::optional<KdStreamVariant> variant,
                     std::span<const Triangle> tris, TriangleTest test, std::string name, double frameMs)
      : triangleTexels_(variant ? triangleVertexTexels(tris) : std::vector<glm::vec4>{}) {
    tracers_.reserve(2);  // the stream data spans point into them
    if (trees.strategy() == DynamicStrategy::Merge) {
      tracers_.emplace_back(trees.mergedTree(), variant, tris, triangleTexels_, test, trees.config().kdStackSize);
    } else {
      tracers_.emplace_back(trees.staticTree(), variant, tris, triangleTexels_, test, trees.config().kdStackSize);
      tracers_.emplace_back(trees.dynamicTree(), variant, tris, triangleTexels_, test, trees.config().kdStackSize);
    }
    stats_.name = std::move(name);
    stats_.buildMs = frameMs;
    for (const TreeTracer& t : tracers_) {
      const AccelStats& s = t.stats();
      stats_.floatsPerTriangle += s.floatsPerTriangle;
      stats_.nodes += s.nodes, stats_.leaves += s.leaves, stats_.references += s.references;
      stats_.depth = std::max(stats_.depth, s.depth);
    }
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    Hit best = tracers_[0].trace(ray, anyHit, stats);
    if (tracers_.size() == 1 || (anyHit && best.found())) return best;
    Ray rest = ray;
    rest.tMax = best.found() ? best.t : ray.tMax;
    const Hit second = tracers_[1].trace(rest, anyHit, stats);
    return second.found() ? second : best;
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

 private:
  std::vector<glm::vec4> triangleTexels_;
  std::vector<TreeTracer> tracers_;
  AccelStats stats_;
};

}  // namespace

std::string_view dynamicStrategyName(DynamicStrategy strategy) {
  switch (strategy) {
    case DynamicStrategy::Rebuild: return "rebuild";
    case DynamicStrategy::TwoTrees: return "two-trees";
    case DynamicStrategy::Merge: return "merge";
  }
  return "?";
}

std::optional<DynamicStrategy> dynamicStrategyByName(std::string_view name) {
  for (DynamicStrategy s : {DynamicStrategy::Rebuild, DynamicStrategy::TwoTrees, DynamicStrategy::Merge})
    if (dynamicStrategyName(s) == name) return s;
  return std::nullopt;
}

std::optional<KdStreamVariant> kdDynamicVariant(std::string_view structureName) {
  // The registry rows reading BuildParam::Dynamic: kd-tree (the CPU stack
  // traversal) and every stream traversal, found by the name it registers.
  if (structureName == "kd-tree") return std::nullopt;
  for (KdStreamVariant v : {KdStreamVariant::Restart, KdStreamVariant::Backtrack, KdStreamVariant::PushDown,
                            KdStreamVariant::ShortStack, KdStreamVariant::PushDownShortStack, KdStreamVariant::Stack})
    if (kdStreamName(v) == structureName) return v;
  throw std::invalid_argument("--dynamic: " + std::string(structureName) + " has no dynamic strategies");
}

KdTree buildKdTreeOver(std::span<const Triangle> tris, std::span<const uint32_t> ids, const AccelBuildConfig& config) {
  std::vector<Triangle> subset;
  subset.reserve(ids.size());
  for (uint32_t id : ids) subset.push_back(tris[id]);
  KdTree tree = buildKdTreeFor(subset, config);
  for (uint32_t& ref : tree.references) ref = ids[ref];
  return tree;
}

KdDynamicTrees::KdDynamicTrees(DynamicStrategy strategy, std::span<const Triangle> tris,
                               const std::vector<uint8_t>& moving, const AccelBuildConfig& config)
    : strategy_(strategy), config_(config), triangleCount_(tris.size()) {
  if (strategy == DynamicStrategy::Rebuild) throw std::invalid_argument("KdDynamicTrees: rebuild keeps no trees");
  std::vector<uint32_t> staticIds;
  for (uint32_t i = 0; i < tris.size(); ++i)
    (i < moving.size() && moving[i] ? movingIds_ : staticIds).push_back(i);
  const auto start = std::chrono::steady_clock::now();
  static_ = buildKdTreeOver(tris, staticIds, config_);
  staticBuildMs_ = millisecondsSince(start);
}

double KdDynamicTrees::update(std::span<const Triangle> tris) {
  if (tris.size() != triangleCount_)
    throw std::runtime_error("--dynamic: the scene has " + std::to_string(tris.size()) + " triangles in this frame, " +
                             std::to_string(triangleCount_) + " in the first: triangle ids must stay the same");
  const auto start = std::chrono::steady_clock::now();
  dynamic_ = buildKdTreeOver(tris, movingIds_, config_);
  if (strategy_ == DynamicStrategy::Merge) merged_ = mergeKdTrees(static_, dynamic_, tris);
  return millisecondsSince(start);
}

std::unique_ptr<CpuAccelerator> makeKdDynamicCpu(const KdDynamicTrees& trees, std::optional<KdStreamVariant> variant,
                                                 std::span<const Triangle> tris, TriangleTest test, std::string name,
                                                 double frameMs) {
  return std::make_unique<DynamicAccelerator>(trees, variant, tris, test, std::move(name), frameMs);
}

}  // namespace passtrace
