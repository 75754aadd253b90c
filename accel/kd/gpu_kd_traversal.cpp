#include "accel/kd/gpu_kd_traversal.h"

#include "accel/kd/kd_texels.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

std::vector<std::string> defines(KdStreamVariant variant, std::string pages, TriangleTest test) {
  if (variant == KdStreamVariant::Backtrack) return {"KD_BACKTRACK", pages, triangleTestDefine(test)};
  return {pages, triangleTestDefine(test)};
}

}  // namespace

GpuKdTraversal::GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                               const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay, AccelStats stats,
                               const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "kd-tree nodes", config.maxPageTexels),
      lists_(texels.lists, "kd-tree triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("kd_init", "kd/kd_init.frag"),
      traverse_(variant == KdStreamVariant::Backtrack ? "kd_backtrack" : "kd_restart", "kd/kd_traverse.frag",
                StreamKernel::Depth::Test, defines(variant, streamPagesDefine({&nodes_, &lists_, &triangles_}),
                                                           config.build.triangleTest)),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2) {
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  traverse_.bindInput("uNodes", nodes_);
  traverse_.bindInput("uLists", lists_);
  traverse_.bindInput("uTriangles", triangles_);
  traverse_.set("uLoopLimit", config.loopLimit);
}

uint64_t GpuKdTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(traverse_, rays);
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
