#pragma once
// Per-ray work counters, shared by every traversal so accelerators can be
// compared by the work they do rather than only by time.

#include <cstdint>

namespace passtrace {

struct RayStats {
  uint32_t steps = 0;          // loop iterations: boxes + triangles visited
  uint32_t triangleTests = 0;  // ray/triangle tests performed
};

}  // namespace passtrace
