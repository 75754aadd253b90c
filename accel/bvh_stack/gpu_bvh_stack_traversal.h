#pragma once
// The stack BVH on the GPU stream renderer: an initialisation kernel, then
// kernels_glsl/bvh_stack/bvh_stack_traverse.frag pass after pass, each ray's
// stack in a storage buffer (bvh_stack_record.glsl) so it survives -l.

#include <memory>
#include <vector>

#include "accel/bvh_stack/bvh_stack_texels.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuBvhStackTraversal final : public GpuTraversal {
 public:
  GpuBvhStackTraversal(const BvhStackTexels& texels, const std::vector<glm::vec4>& triangleTexels, uint32_t stackSize,
                       uint64_t maxStepsPerRay, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream nodes_, references_, triangles_;
  StreamKernel init_, traverse_;
  AccelStats stats_;
  uint32_t stackSize_;
  uint64_t maxPasses_;
  StorageBuffer records_{"bvh-stack ray stacks"};  // grown to the stream's size on the first trace
};

}  // namespace passtrace
