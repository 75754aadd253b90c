#include "accel/bvh/gpu_octant_bvh_traversal.h"

#include "accel/milliseconds_since.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuOctantBvhTraversal::GpuOctantBvhTraversal(OctantZero zero, std::span<const Triangle> tris, AccelStats stats,
                                             const GpuTraversalConfig& config, Fused fused)
    : sequenceSize_(zero.sequence.texels.size()),
      grid_(zero.sequence.grid.value_or(BoxGrid{})),
      triangles_(zero.triangles, "the octant BVH's triangles", config.maxPageTexels),
      // The triangles are in their texture: their array goes before the sequences' texture takes its pages
      // (llvmpipe's are resident once allocated).
      sequences_([&] { std::vector<glm::vec4>().swap(zero.triangles); return kOctants * sequenceSize_; }(),
                 "the eight octant BVH sequences", config.maxPageTexels, kMaxLargeStreamPages),
      kernel_("bvh_octant_traverse", "bvh/bvh_octant_traverse.frag", StreamKernel::Depth::Test,
              {streamPagesDefine({&triangles_}), largeStreamPagesDefine(sequences_),
               triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      loopLimit_(config.loopLimit) {
  // Flattened as they go up: the build's time includes the writing.
  const auto writing = std::chrono::steady_clock::now();
  writeOctantSequences(zero, tris, [&](uint64_t first, std::span<const glm::vec4> texels) {
    sequences_.write(size_t(first), texels);
  });
  zero = {};
  stats_.buildMs += millisecondsSince(writing);
  bindFused(kernel_);  // the traversal pass reads the same walk inputs
  if (fused == Fused::Yes && config.onePassPerBounce)
    fused_ = FusedBounce{"bvh/bvh_octant_fused.frag", {triangleTestDefine(config.build.triangleTest)},
                         {&triangles_}, &sequences_};
}

void GpuOctantBvhTraversal::bindFused(StreamKernel& kernel) const {
  kernel.bindInput("uSequences", sequences_);
  kernel.bindInput("uOctantTriangles", triangles_);
  kernel.set("uSequenceSize", static_cast<uint32_t>(sequenceSize_));
  kernel.set("uLoopLimit", loopLimit_);
  kernel.set("uBoxGridOrigin", grid_.origin);
  kernel.set("uBoxGridStep", grid_.step);
  kernel.set("uBoxGridInvStep", grid_.invStep);
}

uint64_t GpuOctantBvhTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(kernel_, rays);
  rays.setWriteSurfaces({kStateSurface, kHitSurface});
  // Every step advances a ray at least 1 texel in its sequence (a triangle), so no ray needs more passes.
  return runTraversalPasses(kernel_, active, sequenceSize_ / uint64_t(loopLimit_) + 2, retire);
}

}  // namespace passtrace
