#include "accel/gpu_traversal.h"

#include <stdexcept>

#include "accel/bvh/goldsmith_salmon_builder.h"
#include "accel/reference_lists.h"
#include "accel/stream_mirror_accelerators.h"
#include "accel/grid/gpu_grid_traversal.h"
#include "accel/kd/gpu_kd_traversal.h"

#include "accel/bvh/gpu_bvh_traversal.h"
#include "accel/ray_stream_layout.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace {

void bindRayInputs(StreamKernel& kernel, const InOutStream& rays) {
  kernel.bindInput("uOrigin", rays, kOriginSurface);
  kernel.bindInput("uDirection", rays, kDirectionSurface);
  kernel.bindInput("uState", rays, kStateSurface);
  kernel.bindInput("uHit", rays, kHitSurface);
  kernel.bindInput("uAux", rays, kAuxSurface);
}

uint64_t runTraversalPasses(StreamKernel& kernel, uint64_t active, uint64_t maxPasses,
                            const std::function<uint64_t()>& retire) {
  uint64_t passes = 0;
  while (active > 0) {
    if (passes == maxPasses)
      throw GlError(kernel.name() + ": rays still active after " + std::to_string(passes) + " passes");
    kernel.execute();
    ++passes;
    active -= std::min(active, retire());
  }
  return passes;
}

namespace {

constexpr const char* kGpuNames[] = {"kk-bvh", "gs-bvh", "kd-restart", "kd-backtrack", "grid"};

std::unique_ptr<GpuTraversal> makeKdTraversal(int number, const Scene& scene, const GpuTraversalConfig& config) {
  const KdStreamVariant variant = number == 2 ? KdStreamVariant::Restart : KdStreamVariant::Backtrack;
  KdStreamBuild build = buildKdStream(variant, scene.triangles, config.build);
  return std::make_unique<GpuKdTraversal>(variant, build.texels, build.sceneBox, triangleVertexTexels(scene.triangles),
                                          build.maxStepsPerRay, std::move(build.stats), config);
}

std::unique_ptr<GpuTraversal> makeGridTraversal(const Scene& scene, const GpuTraversalConfig& config) {
  GridStreamBuild build = buildGridStream(scene.triangles, config.build);
  const GridStreamData data = makeGridStreamData(build.bounds, build.resolution, {}, {}, {});
  return std::make_unique<GpuGridTraversal>(data, build.texels.cells, build.texels.lists,
                                            triangleVertexTexels(scene.triangles), build.maxStepsPerRay,
                                            std::move(build.stats), config);
}

}  // namespace

std::string gpuAcceleratorName(int number) {
  if (number < 0 || number > 4) throw std::invalid_argument("GPU accelerator " + std::to_string(number) + " does not exist (valid: 0-4)");
  return kGpuNames[number];
}

int gpuAcceleratorNumber(const std::string& nameOrNumber) {
  std::string valid;
  for (int i = 0; i < 5; ++i) {
    if (nameOrNumber == kGpuNames[i] || nameOrNumber == std::to_string(i)) return i;
    valid += (i ? ", " : "") + std::to_string(i) + " " + kGpuNames[i];
  }
  throw std::invalid_argument("unknown GPU accelerator '" + nameOrNumber + "' (valid: " + valid + ")");
}

std::unique_ptr<GpuTraversal> makeGpuTraversal(int number, const Scene& scene, const GpuTraversalConfig& config) {
  if (config.loopLimit < 1) throw std::invalid_argument("the loop limit (-l) must be at least 1");
  switch (number) {
    case 0:
    case 1: {
      SequenceBuild build =
          number == 0 ? buildKayKajiyaSequence(scene.triangles, config.build.kayKajiya)
                      : buildGoldsmithSalmonSequence(scene.triangles,
                                                     GoldsmithSalmonConfig{config.build.gsTries, config.build.gsSeed});
      build.stats.name = kGpuNames[number];
      return std::make_unique<GpuBvhTraversal>(build.sequence, std::move(build.stats), config);
    }
    case 2:
    case 3:
      return makeKdTraversal(number, scene, config);
    case 4:
      return makeGridTraversal(scene, config);
    default:
      throw std::invalid_argument("GPU accelerator " + std::to_string(number) + " does not exist (valid: 0-4)");
  }
}

}  // namespace passtrace
