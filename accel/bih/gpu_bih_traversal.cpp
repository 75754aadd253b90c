#include "accel/bih/gpu_bih_traversal.h"

#include <algorithm>

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuBihTraversal::GpuBihTraversal(const BihTexels& texels, const Aabb& sceneBox,
                                 const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay,
                                 uint32_t stackSize, AccelStats stats, const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "BIH nodes", config.maxPageTexels),
      lists_(texels.lists, "BIH triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("bih_init", "bih/bih_init.frag", StreamKernel::Depth::Test),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2),
      stackSize_(std::max(1u, stackSize)) {
  traverse_ = std::make_unique<StreamKernel>(
      "bih", "bih/bih_traverse.frag", StreamKernel::Depth::Test,
      std::vector<std::string>{streamPagesDefine({&nodes_, &lists_, &triangles_}),
                               triangleTestDefine(config.build.triangleTest)});
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  for (StreamKernel* k : {&init_, traverse_.get()}) {
    k->set("uStackSize", stackSize_);
    k->bindStorage(0, records_);
  }
  traverse_->set("uLoopLimit", config.loopLimit);
  traverse_->bindInput("uNodes", nodes_);
  traverse_->bindInput("uLists", lists_);
  traverse_->bindInput("uTriangles", triangles_);
}

uint64_t GpuBihTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(*traverse_, rays);
  // One record per element: a count and 3 floats per stack entry (bih_ray_record.glsl).
  records_.reserve(uint64_t(rays.elementCount()) * (1 + 3 * uint64_t(stackSize_)));
  for (StreamKernel* k : {&init_, traverse_.get()}) k->set("uStreamWidth", uint32_t(rays.width()));
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(*traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
