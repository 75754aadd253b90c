#include "accel/octree/gpu_octree_traversal.h"

#include <algorithm>

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuOctreeTraversal::GpuOctreeTraversal(const OctreeTexels& texels, const Aabb& rootBox,
                                       const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay,
                                       uint32_t stackSize, AccelStats stats, const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "octree nodes", config.maxPageTexels),
      lists_(texels.lists, "octree triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("octree_init", "octree/octree_init.frag", StreamKernel::Depth::Test),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2),
      stackSize_(std::max(1u, stackSize)) {
  traverse_ = std::make_unique<StreamKernel>(
      "octree", "octree/octree_traverse.frag", StreamKernel::Depth::Test,
      std::vector<std::string>{streamPagesDefine({&nodes_, &lists_, &triangles_}),
                               triangleTestDefine(config.build.triangleTest)});
  init_.set("uEmpty", texels.nodes.empty() ? 1 : 0);
  for (StreamKernel* k : {&init_, traverse_.get()}) {
    k->set("uStackSize", stackSize_);
    k->bindStorage(0, records_);
  }
  traverse_->set("uRootMin", rootBox.min);
  traverse_->set("uRootMax", rootBox.max);
  traverse_->set("uLoopLimit", config.loopLimit);
  traverse_->bindInput("uNodes", nodes_);
  traverse_->bindInput("uLists", lists_);
  traverse_->bindInput("uTriangles", triangles_);
}

uint64_t GpuOctreeTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(*traverse_, rays);
  // One record per element: a count and 8 floats per frame (octree_ray_record.glsl).
  records_.reserve(uint64_t(rays.elementCount()) * (1 + 8 * uint64_t(stackSize_)));
  for (StreamKernel* k : {&init_, traverse_.get()}) k->set("uStreamWidth", uint32_t(rays.width()));
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // every ray, when there are no triangles
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(*traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
