#include "accel/kd/gpu_kd_ropes.h"

#include <algorithm>

#include "accel/kd/kd_ropes.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuKdRopesTraversal::GpuKdRopesTraversal(const KdRopesTexels& texels, const Aabb& sceneBox,
                                         const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay,
                                         AccelStats stats, const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "kd-ropes nodes", config.maxPageTexels),
      lists_(texels.lists, "kd-ropes triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("kd_init", "kd/kd_init.frag", StreamKernel::Depth::Test, {}),
      traverse_("kd_ropes", "kd/kd_ropes_traverse.frag", StreamKernel::Depth::Test,
                {streamPagesDefine({&nodes_, &lists_, &triangles_}), triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2) {
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  traverse_.set("uLoopLimit", config.loopLimit);
  traverse_.set("uMaxSteps", uint32_t(std::min<uint64_t>(maxStepsPerRay, 0xFFFFFFFFu)));
  traverse_.bindInput("uNodes", nodes_);
  traverse_.bindInput("uLists", lists_);
  traverse_.bindInput("uTriangles", triangles_);
}

uint64_t GpuKdRopesTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(traverse_, rays);
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
