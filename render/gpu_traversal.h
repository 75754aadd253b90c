#pragma once
// The one interface the GPU stream renderer traces through: an acceleration
// structure's data streams and traversal kernel(s). Implementations run
// passes over the ray stream (render/ray_stream_layout.h) until the cull
// kernel has retired every active ray.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "accel/cpu_accelerator.h"
#include "scenes/scene.h"

namespace passtrace {

class InOutStream;

class GpuTraversal {
 public:
  virtual ~GpuTraversal() = default;
  // Traces the `active` rays of the enabled stream: reads the origin,
  // direction, state and hit surfaces, writes state and hit. `retire` runs
  // the cull kernel and returns how many rays it retired. Returns the
  // number of traversal passes.
  virtual uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) = 0;
  virtual AccelStats stats() const = 0;
};

struct GpuTraversalConfig {
  AccelBuildConfig build;
  int loopLimit = 20;  // traversal steps per element per pass (tracy's -l)
};

// Builds accelerator `number` (thesis Table 4, GPU column: 0 = K/K BVH) and
// uploads it. Throws std::invalid_argument for a number with no GPU version.
std::unique_ptr<GpuTraversal> makeGpuTraversal(int number, const Scene& scene, const GpuTraversalConfig& config);

}  // namespace passtrace
