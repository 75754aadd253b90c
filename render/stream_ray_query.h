#pragma once
// Tracing rays the caller made through a GPU stream structure
// (accel/gpu_traversal.h): the rays are uploaded as the elements of a ray
// stream, the structure's traversal passes run until the cull kernel has
// retired them all, and the hit surface and the step counters are read back.
// The Python module's Accelerator on renderer "gpu", and the GL tests that
// trace hand-made rays. Needs a current GL context (stream/gl_context.h).
#include <cstdint>
#include <memory>
#include <span>
#include "accel/gpu_traversal.h"

namespace passtrace {

class StreamKernel;

class StreamRayQuery {
 public:
  // Up to this many rays go in one stream; more are traced in several.
  static constexpr int kStreamWidth = 512, kMaxStreamHeight = 512;

  explicit StreamRayQuery(GpuTraversal& traversal);
  ~StreamRayQuery();

  // Traces rays[i] into hits[i]: the closest hit before tMax, or where
  // anyHit[i] is 1 (a shadow ray; anyHit may be empty: none) any hit before
  // it. stats, when not empty, gets each ray's steps and triangle tests as
  // the kernels count them for the heat map; finalStates, when not empty,
  // each ray's state surface after its last pass (the kernel tests read it).
  // Returns the traversal passes.
  uint64_t trace(std::span<const Ray> rays, std::span<const uint8_t> anyHit, std::span<Hit> hits,
                 std::span<RayStats> stats, std::span<glm::vec4> finalStates = {});

 private:
  GpuTraversal& traversal_;
  std::unique_ptr<StreamKernel> cull_;
};

}  // namespace passtrace
