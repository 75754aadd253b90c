#pragma once
// kd-ropes on the GPU: kd_init.frag clips each ray to the scene box (root,
// entry distance), then kernels_glsl/kd/kd_ropes_traverse.frag runs up to -l
// steps of kd_ropes_traversal.glsl per pass. No stack: the node, mode and entry
// distance live in the ray's state and aux texels.
//
// Primary rays start at the root like every other ray (the leaf holding the
// origin is one descent away, at most depth steps): the seed finds the camera's
// leaf once, but GpuTraversal::trace sees neither the camera nor which rays are
// primary, and finding out that all origins are equal would take a reduction
// pass over the origin surface per trace.

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace {

struct KdRopesTexels;

class GpuKdRopesTraversal final : public GpuTraversal {
 public:
  GpuKdRopesTraversal(const KdRopesTexels& texels, const Aabb& sceneBox, const std::vector<glm::vec4>& triangleTexels,
                      uint64_t maxStepsPerRay, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  ConstInputStream nodes_, lists_, triangles_;
  StreamKernel init_;
  StreamKernel traverse_;
  AccelStats stats_;
  uint64_t maxPasses_;
};

}  // namespace passtrace
