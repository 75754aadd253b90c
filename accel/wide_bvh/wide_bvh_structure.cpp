#include "accel/wide_bvh/wide_bvh_structure.h"

#include <chrono>
#include <string>

#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"

namespace passtrace {
namespace {

class Bvh8Accelerator final : public CpuAccelerator {
public:
  Bvh8Accelerator(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    const auto start = std::chrono::steady_clock::now();
    const SahBuildConfig sah;
    const BinaryBvh binary = buildBinnedSahBvh(tris, sah);
    bvh_ = collapseToWideBvh(binary, tris);
    stats_.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_.name = "bvh8";
    stats_.nodes = bvh_.nodes.size() + bvh_.leaves;
    stats_.leaves = bvh_.leaves;
    stats_.references = bvh_.references;
    stats_.depth = bvh_.depth;
    stats_.sahCost = bvhSahCost(binary, sah);
    stats_.structureBytes = bvh_.nodes.size() * sizeof(WideBvhNode) + bvh_.packs.size() * sizeof(TrianglePack);
    // Node floats only (the packs are the triangles): 6 x 8 bounds + 8 child references.
    stats_.floatsPerTriangle = tris.empty() ? 0.0 : double(bvh_.nodes.size()) * 56.0 / double(tris.size());
    traverse_ = wideBvhAvx2Available() ? traverseWideBvhAvx2 : traverseWideBvhScalar;
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverse_(bvh_, tris_, ray, anyHit, test_, stats);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  using Traverse = Hit (*)(const WideBvh&, std::span<const Triangle>, const Ray&, bool, TriangleTest, RayStats*);
  std::span<const Triangle> tris_;
  TriangleTest test_;
  WideBvh bvh_;
  AccelStats stats_;
  Traverse traverse_ = nullptr;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeBvh8Cpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<Bvh8Accelerator>(tris, config.triangleTest);
}

}  // namespace passtrace
