#pragma once
// The uniform grid's registry entries (thesis 9.2): "grid" on the CPU walks
// the grid with a 3D-DDA; on the GPU it runs as stream kernels (merged, the
// thesis's choice, or Purcell's split kernels, --grid-kernels), whose CPU
// form over the same texels is "grid-stream". Reads -g.

#include <cstdint>
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"
#include "accel/grid/grid_texels.h"

namespace passtrace {

// A uniform grid built and flattened for the stream traversal.
struct GridStreamBuild {
  GridTexels texels;
  Aabb bounds;
  glm::ivec3 resolution{1};
  AccelStats stats;
  uint64_t maxStepsPerRay;
};
GridStreamBuild buildGridStream(std::span<const Triangle> tris, const AccelBuildConfig& config);

// The registry's factories (accel/registry.cpp). Statistics: nodes = cells,
// leaves = non-empty cells, references = list entries without terminators,
// depth 1, floatsPerTriangle = flattenGrid's accounting.
std::unique_ptr<CpuAccelerator> makeGridCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeGridStreamMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeGridStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
