#pragma once
// The uniform grid on the GPU (thesis 7.4): an initialisation kernel, then
// either the merged traversal+intersection kernel pass after pass, or
// Purcell's split kernels, the CPU choosing which to run from the occlusion
// counts of the rays each one served.

#include <vector>

#include "accel/grid/grid_stream_traversal.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace {

class GpuGridTraversal final : public GpuTraversal {
 public:
  // `grid` gives the geometry (its spans are not used); the texels are uploaded.
  GpuGridTraversal(const GridStreamData& grid, const std::vector<glm::vec4>& cells,
                   const std::vector<glm::vec4>& lists, const std::vector<glm::vec4>& triangleTexels,
                   uint64_t maxStepsPerRay, AccelStats stats, const GpuTraversalConfig& config);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  uint64_t traceSplit(uint64_t active, const std::function<uint64_t()>& retire);

  ConstInputStream cells_, lists_, triangles_;
  StreamKernel init_, merged_, step_, intersect_;
  AccelStats stats_;
  uint64_t maxStepsPerRay_;
  int loopLimit_;
  GridKernels kernels_;
};

}  // namespace passtrace
