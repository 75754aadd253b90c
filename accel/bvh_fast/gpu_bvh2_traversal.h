#pragma once
// bvh-fast on the GPU: the packed nodes and triangles as ConstInputStreams,
// kernels_glsl/bvh_fast/bvh2_init.frag once per trace, then
// bvh2_traverse.frag pass after pass with the per-ray stack in a storage buffer.

#include <memory>

#include "accel/bvh_fast/bvh2_texels.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuBvh2Traversal final : public GpuTraversal {
 public:
  GpuBvh2Traversal(const Bvh2Texels& texels, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream nodes_;
  ConstInputStream triangles_;
  StorageBuffer stacks_{"the bvh-fast ray stacks"};
  StreamKernel init_;
  StreamKernel traverse_;
  AccelStats stats_;
  uint64_t maxPasses_;
  uint32_t stackDepth_;
};

}  // namespace passtrace
