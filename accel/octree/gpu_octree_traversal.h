#pragma once
// The octree on the GPU with Revelles' traversal: kernels_glsl/octree/
// octree_init.frag, then octree_traverse.frag pass after pass; each element's
// frames live in a storage buffer (octree_ray_record.glsl) so they resume
// across passes under -l.

#include <memory>
#include <vector>

#include "accel/gpu_traversal.h"
#include "accel/octree/octree_texels.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuOctreeTraversal final : public GpuTraversal {
 public:
  // stackSize: frames per element, at least the tree's depth.
  GpuOctreeTraversal(const OctreeTexels& texels, const Aabb& rootBox, const std::vector<glm::vec4>& triangleTexels,
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
  StorageBuffer records_{"octree ray frames"};  // grown to the stream's size on the first trace
};

}  // namespace passtrace
