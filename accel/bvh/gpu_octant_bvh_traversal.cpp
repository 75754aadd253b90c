#include "accel/bvh/gpu_octant_bvh_traversal.h"

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuOctantBvhTraversal::GpuOctantBvhTraversal(BackToBackSequences sequences, AccelStats stats,
                                             const GpuTraversalConfig& config, Fused fused)
    : sequenceSize_(sequences.sequenceSize),
      sequences_(sequences.texels, "the eight octant BVH sequences", config.maxPageTexels),
      kernel_("bvh_octant_traverse", "bvh/bvh_octant_traverse.frag", StreamKernel::Depth::Test,
              {streamPagesDefine({&sequences_}), triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      loopLimit_(config.loopLimit) {
  bindFused(kernel_);  // the traversal pass reads the same walk inputs
  if (fused == Fused::Yes && config.onePassPerBounce)
    fused_ = FusedBounce{"bvh/bvh_octant_fused.frag", {triangleTestDefine(config.build.triangleTest)}, {&sequences_}};
}

void GpuOctantBvhTraversal::bindFused(StreamKernel& kernel) const {
  kernel.bindInput("uSequences", sequences_);
  kernel.set("uSequenceSize", static_cast<uint32_t>(sequenceSize_));
  kernel.set("uLoopLimit", loopLimit_);
}

uint64_t GpuOctantBvhTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(kernel_, rays);
  rays.setWriteSurfaces({kStateSurface, kHitSurface});
  // Every step advances a ray at least 2 texels in its sequence, so no ray needs more passes.
  return runTraversalPasses(kernel_, active, sequenceSize_ / (2 * uint64_t(loopLimit_)) + 2, retire);
}

}  // namespace passtrace
