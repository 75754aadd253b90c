#pragma once
// The BIH on the GPU: kernels_glsl/bih/bih_init.frag, then bih_traverse.frag
// pass after pass; each element's stack lives in a storage buffer
// (bih_ray_record.glsl) so it resumes across passes under -l.

#include <memory>
#include <vector>

#include "accel/bih/bih_texels.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuBihTraversal final : public GpuTraversal {
 public:
  // stackSize: entries per element, at least the tree's depth.
  GpuBihTraversal(const BihTexels& texels, const Aabb& sceneBox, const std::vector<glm::vec4>& triangleTexels,
                  uint64_t maxStepsPerRay, uint32_t stackSize, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream nodes_, lists_, triangles_;
  StreamKernel init_;
  std::unique_ptr<StreamKernel> traverse_;
  AccelStats stats_;
  uint64_t maxPasses_;
  uint32_t stackSize_;
  StorageBuffer records_{"BIH ray stacks"};  // grown to the stream's size on the first trace
};

}  // namespace passtrace
