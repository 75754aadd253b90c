#include "accel/kd/gpu_kd_traversal.h"

#include "accel/kd/kd_texels.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

std::vector<std::string> defines(KdStreamVariant variant, std::string pages, TriangleTest test) {
  std::vector<std::string> out = {pages, triangleTestDefine(test)};
  if (variant == KdStreamVariant::Backtrack) out.push_back("KD_BACKTRACK");
  if (kdRestartsFromPushDownRoot(variant)) out.push_back("KD_PUSHDOWN");
  if (kdHasStack(variant)) out.push_back("KD_STACK");
  if (kdHasRayRecord(variant)) out.push_back("KD_RECORD");
  return out;
}

std::string kernelName(KdStreamVariant variant) {
  switch (variant) {
    case KdStreamVariant::Restart: return "kd_restart";
    case KdStreamVariant::Backtrack: return "kd_backtrack";
    case KdStreamVariant::PushDown: return "kd_pushdown";
    case KdStreamVariant::ShortStack: return "kd_shortstack";
    case KdStreamVariant::PushDownShortStack: return "kd_pushdown_shortstack";
    case KdStreamVariant::Stack: return "kd_stack";
  }
  return "kd";
}

}  // namespace

GpuKdTraversal::GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                               const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay, uint32_t stackSize,
                               AccelStats stats, const GpuTraversalConfig& config)
    : nodes_(texels.nodes, "kd-tree nodes", config.maxPageTexels),
      lists_(texels.lists, "kd-tree triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("kd_init", "kd/kd_init.frag", StreamKernel::Depth::Test,
            kdHasRayRecord(variant) ? std::vector<std::string>{"KD_RECORD"} : std::vector<std::string>{}),
      traverse_(kernelName(variant), "kd/kd_traverse.frag", StreamKernel::Depth::Test,
                defines(variant, streamPagesDefine({&nodes_, &lists_, &triangles_}), config.build.triangleTest)),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2),
      hasRecord_(kdHasRayRecord(variant)),
      stackSize_(stackSize) {
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  traverse_.bindInput("uNodes", nodes_);
  traverse_.bindInput("uLists", lists_);
  traverse_.bindInput("uTriangles", triangles_);
  traverse_.set("uLoopLimit", config.loopLimit);
  if (hasRecord_) {
    for (StreamKernel* k : {&init_, &traverse_}) {
      k->set("uStackSize", stackSize_);
      k->bindStorage(0, records_);
    }
  }
}

uint64_t GpuKdTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(traverse_, rays);
  if (hasRecord_) {
    // One record per element: 4 header floats and 3 per stack entry (kd_ray_record.glsl).
    records_.reserve(uint64_t(rays.elementCount()) * (4 + 3 * uint64_t(stackSize_)));
    for (StreamKernel* k : {&init_, &traverse_}) k->set("uStreamWidth", uint32_t(rays.width()));
  }
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
