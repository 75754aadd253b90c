#include "accel/kd/kd_accelerator.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_pbrt_builder.h"

namespace passtrace {
namespace {

class KdAccelerator final : public CpuAccelerator {
public:
  KdAccelerator(int number, std::span<const Triangle> tris, const AccelBuildConfig& config)
      : tris_(tris), test_(config.triangleTest) {
    const auto start = std::chrono::steady_clock::now();
    tree_ = number == 2 ? buildKdTree(tris, kdConfigFor(config)) : buildKdTreePbrt(tris, kdPbrtConfigFor(config));
    stats_.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_.name = acceleratorName(number);
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

std::unique_ptr<CpuAccelerator> makeKdCpuAccelerator(int number, std::span<const Triangle> tris,
                                                     const AccelBuildConfig& config) {
  if (number != 2 && number != 3)
    throw std::invalid_argument("makeKdCpuAccelerator: accelerator " + std::to_string(number) + " is not a kd-tree");
  return std::make_unique<KdAccelerator>(number, tris, config);
}

}  // namespace passtrace
