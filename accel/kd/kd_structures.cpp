#include "accel/kd/kd_structures.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/kd/gpu_kd_traversal.h"
#include "accel/kd/kd_binned_builder.h"
#include "accel/kd/kd_sah_cost.h"
#include "accel/kd/kd_termination.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "accel/milliseconds_since.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {


// kd-tree and kd-pbrt: the tree walked with a stack (kd_traversal.h).
class KdAccelerator final : public CpuAccelerator {
public:
  KdAccelerator(const char* name, KdTree tree, double buildMs, std::span<const Triangle> tris, TriangleTest test)
      : tris_(tris), tree_(std::move(tree)), test_(test) {
    stats_.buildMs = buildMs;
    stats_.name = name;
    stats_.floatsPerTriangle = kdFloatsPerTriangle(tree_, tris.size(), kKdRestartStride);
    setKdTreeStats(stats_, tree_);
    stats_.structureBytes = tree_.nodes.size() * sizeof(KdNode) + tree_.references.size() * sizeof(uint32_t);
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseKdTree(tree_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  KdTree tree_;
  AccelStats stats_;
  TriangleTest test_;
};

// kd-restart and kd-backtrack on the CPU: the kernel's algorithm over the
// texels the GPU reads, so both count the same steps.
class KdStreamMirror final : public CpuAccelerator {
 public:
  KdStreamMirror(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildKdStream(variant, tris, config)) {
    data_ = KdStreamData{variant, build_.sceneBox, build_.texels.nodes, build_.texels.lists, triangles_,
                         config.triangleTest, build_.stackSize};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseKdStream(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  KdStreamBuild build_;
  KdStreamData data_;
};

std::unique_ptr<GpuTraversal> makeStream(KdStreamVariant variant, std::span<const Triangle> tris,
                                         const GpuTraversalConfig& config) {
  KdStreamBuild build = buildKdStream(variant, tris, config.build);
  return std::make_unique<GpuKdTraversal>(variant, build.texels, build.sceneBox, triangleVertexTexels(tris),
                                          build.maxStepsPerRay, build.stackSize, std::move(build.stats), config);
}

}  // namespace

const char* kdStreamName(KdStreamVariant variant) {
  switch (variant) {
    case KdStreamVariant::Restart: return "kd-restart";
    case KdStreamVariant::Backtrack: return "kd-backtrack";
    case KdStreamVariant::PushDown: return "kd-pushdown";
    case KdStreamVariant::ShortStack: return "kd-shortstack";
    case KdStreamVariant::PushDownShortStack: return "kd-pushdown-shortstack";
    case KdStreamVariant::Stack: return "kd-stack";
    case KdStreamVariant::Compact: return "kd-compact";
  }
  return "?";
}

KdBuildConfig kdConfigFor(const AccelBuildConfig& config) {
  KdBuildConfig kd;
  kd.maxDepth = config.kdMaxDepth;
  kd.minElements = config.kdMinElements;
  return kd;
}

KdTree buildKdTreeFor(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const KdBuildConfig kd = kdWithTermination(kdConfigFor(config), config.kdTermination, tris.size());
  return config.kdBuilder == KdBuilderKind::Binned ? buildKdTreeBinned(tris, kd) : buildKdTree(tris, kd);
}

void setKdTreeStats(AccelStats& stats, const KdTree& tree) {
  const KdBuildConfig constants;
  stats.nodes = tree.nodes.size();
  stats.leaves = tree.leafCount();
  stats.references = tree.references.size();
  stats.depth = tree.depth();
  stats.sahCost = kdSahCost(tree, constants.traversalCost, constants.intersectionCost);
}

KdBuildConfig kdPbrtConfigFor(const AccelBuildConfig& config) {
  KdBuildConfig kd = kPbrtKdConfig;
  if (config.kdMaxDepth > 0) kd.maxDepth = config.kdMaxDepth;
  return kd;
}

KdStreamBuild flattenKdStream(KdStreamVariant variant, const KdTree& tree, size_t triangleCount,
                              int shortStackSize) {
  KdStreamBuild build{variant == KdStreamVariant::Backtrack ? flattenKdBacktrack(tree, triangleCount)
                      : variant == KdStreamVariant::Compact ? flattenKdCompact(tree, triangleCount)
                                                            : flattenKdRestart(tree, triangleCount),
                      tree.bounds, AccelStats{}, 0};
  AccelStats& s = build.stats;
  s.name = kdStreamName(variant);
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  setKdTreeStats(s, tree);
  s.structureBytes = (build.texels.nodes.size() + build.texels.lists.size()) * sizeof(glm::vec4);
  // Each leaf is searched at most once (plus a re-entry per backtrack), reached through at most depth nodes.
  // Push-down takes a subset of restart's steps; a stack pop or restart
  // reaches a leaf through at most depth nodes like a restart does.
  build.maxStepsPerRay = 2 * (uint64_t(s.leaves) + 1) * (s.depth + 2) + 2 * s.nodes + build.texels.listEntries;
  if (variant == KdStreamVariant::Stack || variant == KdStreamVariant::Compact) {
    // A path holds depth - 1 internal nodes, each pushing at most one entry.
    build.stackSize = std::max<uint32_t>(1, s.depth);
  } else if (kdHasStack(variant)) {
    if (shortStackSize < 1 || shortStackSize > 8)
      throw std::invalid_argument("the kd short-stack size (--stack-size) must be 1 to 8");
    build.stackSize = uint32_t(shortStackSize);
  }
  return build;
}

KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const KdTree tree = buildKdTreeFor(tris, config);
  KdStreamBuild build = flattenKdStream(variant, tree, tris.size(), config.kdStackSize);
  build.stats.buildMs = millisecondsSince(start);
  return build;
}

std::unique_ptr<CpuAccelerator> makeKdTreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  KdTree tree = buildKdTreeFor(tris, config);
  return std::make_unique<KdAccelerator>("kd-tree", std::move(tree), millisecondsSince(start), tris,
                                         config.triangleTest);
}

std::unique_ptr<CpuAccelerator> makeKdPbrtCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  KdTree tree = buildKdTreePbrt(tris, kdPbrtConfigFor(config));
  return std::make_unique<KdAccelerator>("kd-pbrt", std::move(tree), millisecondsSince(start), tris,
                                         config.triangleTest);
}

std::unique_ptr<CpuAccelerator> makeKdRestartMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<KdStreamMirror>(KdStreamVariant::Restart, tris, config);
}

std::unique_ptr<CpuAccelerator> makeKdBacktrackMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<KdStreamMirror>(KdStreamVariant::Backtrack, tris, config);
}

std::unique_ptr<GpuTraversal> makeKdRestartStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  return makeStream(KdStreamVariant::Restart, tris, config);
}

std::unique_ptr<GpuTraversal> makeKdBacktrackStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  return makeStream(KdStreamVariant::Backtrack, tris, config);
}

template <KdStreamVariant V>
std::unique_ptr<CpuAccelerator> makeKdStreamMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<KdStreamMirror>(V, tris, config);
}

template <KdStreamVariant V>
std::unique_ptr<GpuTraversal> makeKdStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  return makeStream(V, tris, config);
}

#define PASSTRACE_KD_STREAM_VARIANT(V)                                                                       \
  template std::unique_ptr<CpuAccelerator> makeKdStreamMirror<V>(std::span<const Triangle>,                  \
                                                                 const AccelBuildConfig&);                  \
  template std::unique_ptr<GpuTraversal> makeKdStream<V>(std::span<const Triangle>, const GpuTraversalConfig&);
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::Restart)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::Backtrack)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::PushDown)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::ShortStack)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::PushDownShortStack)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::Stack)
PASSTRACE_KD_STREAM_VARIANT(KdStreamVariant::Compact)
#undef PASSTRACE_KD_STREAM_VARIANT

}  // namespace passtrace
