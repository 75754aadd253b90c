#include "accel/kd/gpu_kd_dynamic.h"

#include <algorithm>
#include <chrono>

#include "accel/kd/kd_structures.h"
#include "accel/milliseconds_since.h"
#include "accel/reference_lists.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

using Clock = std::chrono::steady_clock;

// Two trees reported as one structure: sizes added, the deeper depth.
AccelStats combined(const AccelStats& a, const AccelStats& b) {
  AccelStats s = a;
  s.floatsPerTriangle += b.floatsPerTriangle;
  s.nodes += b.nodes, s.leaves += b.leaves, s.references += b.references;
  s.depth = std::max(a.depth, b.depth);
  return s;
}

}  // namespace

GpuKdDynamicTraversal::GpuKdDynamicTraversal(const KdDynamicTrees& trees, KdStreamVariant variant,
                                             std::span<const Triangle> tris, const GpuTraversalConfig& config)
    : trees_(trees), variant_(variant) {
  const std::vector<glm::vec4> triangles = triangleVertexTexels(tris);
  const bool merge = trees.strategy() == DynamicStrategy::Merge;
  auto start = Clock::now();
  const KdStreamBuild first = flattenKdStream(variant, merge ? trees.mergedTree() : trees.staticTree(), tris.size(),
                                               config.build.kdStackSize);
  if (merge) firstFlattenMs_ = millisecondsSince(start);
  first_ = std::make_unique<GpuKdTraversal>(variant, first.texels, first.sceneBox, triangles, first.maxStepsPerRay,
                                            first.stackSize, first.stats, config);
  stats_ = first.stats;
  if (!merge) {
    staticStats_ = first.stats;
    start = Clock::now();
    const KdStreamBuild second = flattenKdStream(variant, trees.dynamicTree(), tris.size(), config.build.kdStackSize);
    firstFlattenMs_ = millisecondsSince(start);
    second_ = std::make_unique<GpuKdTraversal>(variant, second.texels, second.sceneBox, triangles,
                                               second.maxStepsPerRay, second.stackSize, second.stats, config, true);
    stats_ = combined(staticStats_, second.stats);
  }
}

double GpuKdDynamicTraversal::update(std::span<const Triangle> tris) {
  const auto start = Clock::now();
  const bool merge = trees_.strategy() == DynamicStrategy::Merge;
  const KdStreamBuild build = flattenKdStream(variant_, merge ? trees_.mergedTree() : trees_.dynamicTree(), tris.size(),
                                               trees_.config().kdStackSize);
  const double ms = millisecondsSince(start);
  const std::vector<glm::vec4> triangles = triangleVertexTexels(tris);
  GpuKdTraversal& frameTree = merge ? *first_ : *second_;
  frameTree.replaceTree(build.texels, build.sceneBox, build.maxStepsPerRay, build.stackSize, build.stats);
  frameTree.replaceTriangles(triangles);  // two-trees: the static tree lists only triangles that do not move
  stats_ = merge ? build.stats : combined(staticStats_, build.stats);
  return ms;
}

uint64_t GpuKdDynamicTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  if (!second_) return first_->trace(rays, active, retire);
  rays.saveDepth();
  uint64_t passes = first_->trace(rays, active, retire);
  rays.restoreDepth();
  passes += second_->trace(rays, active, retire);
  return passes;
}

}  // namespace passtrace
