#pragma once
// The kd-tree stream traversals on the GPU (thesis 8.5, seed 003 ch. 6): an
// initialisation kernel, then kernels_glsl/kd/kd_traverse.frag pass after
// pass. The push-down and stack variants keep a per-element record (restart
// root, push-down flag, stack) in a storage buffer (kd_ray_record.glsl).

#include <vector>

#include "accel/kd/kd_stream_traversal.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

struct KdTexels;

class GpuKdTraversal final : public GpuTraversal {
 public:
  GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                 const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay, uint32_t stackSize,
                 AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream nodes_, lists_, triangles_;
  StreamKernel init_, traverse_;
  AccelStats stats_;
  uint64_t maxPasses_;
  bool hasRecord_;
  uint32_t stackSize_;
  StorageBuffer records_{"kd-tree ray stacks"};  // grown to the stream's size on the first trace
};

}  // namespace passtrace
