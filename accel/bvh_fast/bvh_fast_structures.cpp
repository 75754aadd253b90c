#include "accel/bvh_fast/bvh_fast_structures.h"

#include <chrono>

#include "accel/bvh/bvh_structures.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/bvh_fast/bvh2_traversal.h"
#include "accel/bvh_fast/gpu_bvh2_traversal.h"

namespace passtrace {
namespace {

struct Bvh2Build {
  Bvh2Texels texels;
  AccelStats stats;
};

Bvh2Build build(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildKayKajiya(tris, config.kayKajiya);
  Bvh2Build out{packBvh2(bvh, tris), bvhStats("bvh-fast", bvh)};
  out.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  // 4 texels per internal node, triangles excluded (thesis Table 3 accounting).
  out.stats.floatsPerTriangle = tris.empty() ? 0.0 : 16.0 * double(out.texels.nodes.size() / 4) / double(tris.size());
  out.stats.structureBytes = out.texels.nodes.size() * sizeof(glm::vec4);
  return out;
}

}  // namespace

std::unique_ptr<CpuAccelerator> makeBvhFastMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  Bvh2Build b = build(tris, config);
  return makeBvh2Mirror(std::move(b.texels), std::move(b.stats), config.triangleTest);
}

std::unique_ptr<GpuTraversal> makeBvhFastStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  Bvh2Build b = build(tris, config.build);
  return std::make_unique<GpuBvh2Traversal>(b.texels, std::move(b.stats), config);
}

}  // namespace passtrace
