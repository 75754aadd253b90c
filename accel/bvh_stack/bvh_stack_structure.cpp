#include "accel/bvh_stack/bvh_stack_structure.h"

#include <algorithm>
#include <chrono>

#include "accel/bvh_stack/bvh_stack_traversal.h"
#include "accel/bvh_stack/gpu_bvh_stack_traversal.h"
#include "accel/bvh_stack/middle_builder.h"
#include "accel/bvh_stack/sah_builder.h"
#include "accel/bvh_stack/sbvh_builder.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

class BvhStackMirror final : public CpuAccelerator {
 public:
  BvhStackMirror(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildBvhStack(tris, config)) {
    data_ = BvhStackData{build_.texels.nodes, build_.texels.references, triangles_, config.triangleTest,
                         build_.stackSize};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseBvhStack(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  BvhStackBuild build_;
  BvhStackData data_;
};

}  // namespace

BinaryBvh buildBvhStackTree(std::span<const Triangle> tris, BvhBuilderKind builder, const BvhStackConfig& config) {
  switch (builder) {
    case BvhBuilderKind::Sah: return buildBinnedSah(tris, config);
    case BvhBuilderKind::Sbvh: return buildSbvh(tris, config);
    case BvhBuilderKind::Middle: return buildMiddleCut(tris, config);
  }
  return {};
}

BvhStackBuild buildBvhStack(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const BvhStackConfig constants;
  const BinaryBvh bvh = buildBvhStackTree(tris, config.bvhBuilder, constants);
  BvhStackBuild build{flattenBvhStack(bvh, tris.size()), AccelStats{}, std::max(1u, bvh.depth), 0};
  AccelStats& s = build.stats;
  s.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  s.name = "bvh-stack";
  const bool loneLeaf = bvh.nodes.size() == 1 && !bvh.nodes[0].child[1].present;
  s.leaves = bvh.leaves;
  s.nodes = loneLeaf ? 1 : bvh.nodes.size() + bvh.leaves;
  s.references = bvh.references.size();
  s.depth = bvh.depth;
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  s.sahCost = binaryBvhSahCost(bvh, constants.traversalCost, constants.intersectionCost);
  s.structureBytes = (build.texels.nodes.size() + build.texels.references.size()) * sizeof(glm::vec4);
  build.maxStepsPerRay = bvh.nodes.size() + bvh.references.size() + 2;
  return build;
}

std::unique_ptr<CpuAccelerator> makeBvhStackCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<BvhStackMirror>(tris, config);
}

std::unique_ptr<GpuTraversal> makeBvhStackStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  BvhStackBuild build = buildBvhStack(tris, config.build);
  return std::make_unique<GpuBvhStackTraversal>(build.texels, triangleVertexTexels(tris), build.stackSize,
                                                build.maxStepsPerRay, std::move(build.stats), config);
}

}  // namespace passtrace
