#include "accel/kd/kd_structures.h"

#include <chrono>
#include <string>
#include <vector>

#include "accel/kd/gpu_kd_traversal.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// kd-tree and kd-pbrt: the tree walked with a stack (kd_traversal.h).
class KdAccelerator final : public CpuAccelerator {
public:
  KdAccelerator(const char* name, KdTree tree, double buildMs, std::span<const Triangle> tris, TriangleTest test)
      : tris_(tris), tree_(std::move(tree)), test_(test) {
    stats_.buildMs = buildMs;
    stats_.name = name;
    stats_.floatsPerTriangle = kdFloatsPerTriangle(tree_, tris.size(), kKdRestartStride);
    stats_.nodes = tree_.nodes.size();
    stats_.leaves = tree_.leafCount();
    stats_.references = tree_.references.size();
    stats_.depth = tree_.depth();
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
                         config.triangleTest};
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
                                          build.maxStepsPerRay, std::move(build.stats), config);
}

}  // namespace

KdBuildConfig kdConfigFor(const AccelBuildConfig& config) {
  KdBuildConfig kd;
  kd.maxDepth = config.kdMaxDepth;
  kd.minElements = config.kdMinElements;
  return kd;
}

KdBuildConfig kdPbrtConfigFor(const AccelBuildConfig& config) {
  KdBuildConfig kd = kPbrtKdConfig;
  if (config.kdMaxDepth > 0) kd.maxDepth = config.kdMaxDepth;
  return kd;
}

KdStreamBuild flattenKdStream(KdStreamVariant variant, const KdTree& tree, size_t triangleCount) {
  KdStreamBuild build{variant == KdStreamVariant::Restart ? flattenKdRestart(tree, triangleCount)
                                                          : flattenKdBacktrack(tree, triangleCount),
                      tree.bounds, AccelStats{}, 0};
  AccelStats& s = build.stats;
  s.name = variant == KdStreamVariant::Restart ? "kd-restart" : "kd-backtrack";
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  s.nodes = tree.nodes.size();
  s.leaves = tree.leafCount();
  s.references = tree.references.size();
  s.depth = tree.depth();
  // Each leaf is searched at most once (plus a re-entry per backtrack), reached through at most depth nodes.
  build.maxStepsPerRay = 2 * (uint64_t(s.leaves) + 1) * (s.depth + 2) + 2 * s.nodes + build.texels.listEntries;
  return build;
}

KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const KdTree tree = buildKdTree(tris, kdConfigFor(config));
  KdStreamBuild build = flattenKdStream(variant, tree, tris.size());
  build.stats.buildMs = millisecondsSince(start);
  return build;
}

std::unique_ptr<CpuAccelerator> makeKdTreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  KdTree tree = buildKdTree(tris, kdConfigFor(config));
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

}  // namespace passtrace
