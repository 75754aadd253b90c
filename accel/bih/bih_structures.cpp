#include "accel/bih/bih_structures.h"

#include <algorithm>
#include <chrono>

#include "accel/bih/bih.h"
#include "accel/bih/bih_stream_traversal.h"
#include "accel/bih/bih_texels.h"
#include "accel/bih/gpu_bih_traversal.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

struct BihBuild {
  BihTexels texels;
  Aabb sceneBox;
  AccelStats stats;
  uint64_t maxStepsPerRay = 0;
  uint32_t stackSize = 1;
};

BihBuild buildBihStream(std::span<const Triangle> tris) {
  const auto start = std::chrono::steady_clock::now();
  const Bih bih = buildBih(tris);
  BihBuild b{flattenBih(bih, tris.size()), bih.bounds, AccelStats{}};
  AccelStats& s = b.stats;
  s.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  s.name = "bih";
  s.floatsPerTriangle = b.texels.floatsPerTriangle;
  s.nodes = bih.nodes.size();
  s.leaves = bih.leafCount();
  s.references = bih.references.size();
  s.depth = bih.depth;
  s.structureBytes = (b.texels.nodes.size() + b.texels.lists.size()) * sizeof(glm::vec4);
  // Each node is entered at most once (one step) and culled at most once when
  // popped; each list entry is one step.
  b.maxStepsPerRay = 2 * uint64_t(s.nodes) + b.texels.listEntries + 2;
  // The stack holds at most one far child per inner node on the current path.
  b.stackSize = std::max<uint32_t>(1, bih.depth);
  return b;
}

class BihCpu final : public CpuAccelerator {
 public:
  BihCpu(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildBihStream(tris)) {
    data_ = BihStreamData{build_.sceneBox, build_.texels.nodes, build_.texels.lists, triangles_, config.triangleTest};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseBihStream(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  BihBuild build_;
  BihStreamData data_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeBihCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<BihCpu>(tris, config);
}

std::unique_ptr<GpuTraversal> makeBihStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  BihBuild b = buildBihStream(tris);
  return std::make_unique<GpuBihTraversal>(b.texels, b.sceneBox, triangleVertexTexels(tris), b.maxStepsPerRay,
                                           b.stackSize, std::move(b.stats), config);
}

}  // namespace passtrace
