#include "accel/octree/octree_structure.h"

#include <chrono>
#include <string>

#include "accel/octree/octree.h"

namespace passtrace {
namespace {

class OctreeAccelerator final : public CpuAccelerator {
public:
  OctreeAccelerator(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    const auto start = std::chrono::steady_clock::now();
    octree_ = buildOctree(tris);
    stats_.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_.name = "octree";
    stats_.nodes = octree_.nodes.size();
    stats_.leaves = octree_.leafCount();
    stats_.references = octree_.references.size();
    stats_.depth = octree_.depth;
    stats_.floatsPerTriangle = octree_.floatsPerTriangle(tris.size());
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseOctree(octree_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  Octree octree_;
  AccelStats stats_;
  TriangleTest test_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeOctreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<OctreeAccelerator>(tris, config.triangleTest);
}

}  // namespace passtrace
