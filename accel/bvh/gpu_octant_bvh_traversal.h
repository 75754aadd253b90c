#pragma once
// The octant-ordered escape-index BVH on the GPU: the eight sequences of
// accel/bvh/octant_sequences.h in one ConstInputStream, their triangles'
// second and third vertices in another (LeafTexels::Shared), walked by
// kernels_glsl/bvh/bvh_octant_traverse.frag; with Fused::Yes (bvh-octant-fused)
// it also offers kernels_glsl/bvh/bvh_octant_fused.frag for a primary bounce.

#include <optional>
#include <span>

#include "accel/bvh/octant_sequences.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuOctantBvhTraversal final : public GpuTraversal {
 public:
  enum class Fused { No, Yes };
  // Writes the eight sequences from `zero` octant by octant (writeOctantSequences), then lets it go.
  GpuOctantBvhTraversal(OctantZero zero, std::span<const Triangle> tris, AccelStats stats,
                        const GpuTraversalConfig& config, Fused fused = Fused::No);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }
  const FusedBounce* fusedBounce() const override { return fused_ ? &*fused_ : nullptr; }
  void bindFused(StreamKernel& kernel) const override;

 private:
  uint64_t sequenceSize_;
  BoxGrid grid_;
  ConstInputStream triangles_;  // before sequences_: made first (see the constructor)
  ConstInputStream sequences_;
  StreamKernel kernel_;
  AccelStats stats_;
  int loopLimit_;
  std::optional<FusedBounce> fused_;
};

}  // namespace passtrace
