#include "render/gpu_bvh_traversal.h"

#include "render/ray_stream_layout.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuBvhTraversal::GpuBvhTraversal(const EscapeSequence& sequence, AccelStats stats, int loopLimit)
    : sequence_(sequence.texels, "the BVH escape-index sequence"),
      kernel_("bvh_traverse", "bvh_traverse.frag"),
      stats_(std::move(stats)),
      loopLimit_(loopLimit) {
  kernel_.bindInput("uSequence", sequence_);
  kernel_.set("uSequenceSize", static_cast<uint32_t>(sequence.texels.size()));
  kernel_.set("uLoopLimit", loopLimit);
}

uint64_t GpuBvhTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  kernel_.bindInput("uOrigin", rays, kOriginSurface);
  kernel_.bindInput("uDirection", rays, kDirectionSurface);
  kernel_.bindInput("uState", rays, kStateSurface);
  kernel_.bindInput("uHit", rays, kHitSurface);
  rays.setWriteSurfaces({kStateSurface, kHitSurface});
  // Every step advances a ray at least 2 texels, so no ray needs more passes
  // than this; reaching it means a kernel bug, not a slow scene.
  const uint64_t maxPasses = sequence_.size() / (2 * uint64_t(loopLimit_)) + 2;
  uint64_t passes = 0;
  while (active > 0) {
    if (passes == maxPasses) throw GlError("bvh_traverse: rays still active after " + std::to_string(passes) + " passes");
    kernel_.execute();
    ++passes;
    const uint64_t retired = retire();
    active -= std::min(retired, active);
  }
  return passes;
}

}  // namespace passtrace
