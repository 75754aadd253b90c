#include "accel/bvh_stack/gpu_bvh_stack_traversal.h"

#include <algorithm>

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuBvhStackTraversal::GpuBvhStackTraversal(const BvhStackTexels& texels, const std::vector<glm::vec4>& triangleTexels,
                                           uint32_t stackSize, uint64_t maxStepsPerRay, AccelStats stats,
                                           const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "stack BVH nodes", config.maxPageTexels),
      references_(texels.references, "stack BVH references", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("bvh_stack_init", "bvh_stack/bvh_stack_init.frag", StreamKernel::Depth::Test, {}),
      traverse_("bvh_stack", "bvh_stack/bvh_stack_traverse.frag", StreamKernel::Depth::Test,
                {streamPagesDefine({&nodes_, &references_, &triangles_}),
                 triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      stackSize_(std::max(1u, stackSize)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2) {
  init_.set("uEmpty", int(texels.nodes.empty()));
  traverse_.bindInput("uNodes", nodes_);
  traverse_.bindInput("uReferences", references_);
  traverse_.bindInput("uTriangles", triangles_);
  traverse_.set("uLoopLimit", config.loopLimit);
  for (StreamKernel* k : {&init_, &traverse_}) {
    k->set("uStackSize", stackSize_);
    k->bindStorage(0, records_);
  }
}

uint64_t GpuBvhStackTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(traverse_, rays);
  // One record per element: the entry count and 3 floats per entry (bvh_stack_record.glsl).
  records_.reserve(uint64_t(rays.elementCount()) * (1 + 3 * uint64_t(stackSize_)));
  for (StreamKernel* k : {&init_, &traverse_}) k->set("uStreamWidth", uint32_t(rays.width()));
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // every ray of an empty tree
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
