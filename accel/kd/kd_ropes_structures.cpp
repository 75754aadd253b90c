#include "accel/kd/kd_ropes_structures.h"

#include <chrono>
#include <vector>

#include "accel/kd/gpu_kd_ropes.h"
#include "accel/kd/kd_ropes.h"
#include "accel/kd/kd_ropes_traversal.h"
#include "accel/kd/kd_structures.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

// The tree, its ropes and texels, as the GPU uploads them.
struct KdRopesBuild {
  KdRopesTexels texels;
  Aabb sceneBox;
  AccelStats stats;
  uint64_t maxStepsPerRay = 0;
};

KdRopesBuild buildKdRopesStream(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const KdTree tree = buildKdTreeFor(tris, config);
  KdRopesBuild build{flattenKdRopes(tree, buildKdRopes(tree), tris.size()), tree.bounds, AccelStats{}, 0};
  AccelStats& s = build.stats;
  s.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  s.name = "kd-ropes";
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  setKdTreeStats(s, tree);
  s.structureBytes = (build.texels.nodes.size() + build.texels.lists.size()) * sizeof(glm::vec4);
  build.maxStepsPerRay = kdRopesMaxSteps(s.leaves, s.depth, build.texels.listEntries);
  return build;
}

class KdRopesMirror final : public CpuAccelerator {
 public:
  KdRopesMirror(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildKdRopesStream(tris, config)) {
    data_ = KdRopesData{build_.sceneBox, build_.texels.nodes, build_.texels.lists, triangles_, config.triangleTest,
                        build_.maxStepsPerRay};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseKdRopes(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  KdRopesBuild build_;
  KdRopesData data_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeKdRopesMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<KdRopesMirror>(tris, config);
}

std::unique_ptr<GpuTraversal> makeKdRopesStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  KdRopesBuild build = buildKdRopesStream(tris, config.build);
  return std::make_unique<GpuKdRopesTraversal>(build.texels, build.sceneBox, triangleVertexTexels(tris),
                                               build.maxStepsPerRay, std::move(build.stats), config);
}

}  // namespace passtrace
