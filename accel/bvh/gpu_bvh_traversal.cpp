#include "accel/bvh/gpu_bvh_traversal.h"

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuBvhTraversal::GpuBvhTraversal(const EscapeSequence& sequence, AccelStats stats, const GpuTraversalConfig& config)
    : sequence_(sequence.texels, "the BVH escape-index sequence", config.maxPageTexels),
      kernel_("bvh_traverse", "bvh/bvh_traverse.frag", StreamKernel::Depth::Test, {streamPagesDefine({&sequence_}), triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      loopLimit_(config.loopLimit) {
  kernel_.bindInput("uSequence", sequence_);
  kernel_.set("uSequenceSize", static_cast<uint32_t>(sequence.texels.size()));
  kernel_.set("uLoopLimit", loopLimit_);
}

uint64_t GpuBvhTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(kernel_, rays);
  rays.setWriteSurfaces({kStateSurface, kHitSurface});
  // Every step advances a ray at least 2 texels, so no ray needs more passes.
  return runTraversalPasses(kernel_, active, sequence_.size() / (2 * uint64_t(loopLimit_)) + 2, retire);
}

}  // namespace passtrace
