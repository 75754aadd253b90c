#pragma once
// Escape-index BVH traversal on the GPU (thesis 9.4): the sequence as a
// ConstInputStream and kernels_glsl/bvh/bvh_traverse.frag.

#include "accel/bvh/escape_sequence.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuBvhTraversal final : public GpuTraversal {
 public:
  GpuBvhTraversal(const EscapeSequence& sequence, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream sequence_;
  StreamKernel kernel_;
  AccelStats stats_;
  int loopLimit_;
};

}  // namespace passtrace
