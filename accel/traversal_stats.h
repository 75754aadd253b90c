#pragma once
// Per-ray work counters, shared by every traversal so accelerators can be
// compared by the work they do rather than only by time.

#include <cstdint>

namespace passtrace {

struct RayStats {
  uint32_t steps = 0;          // loop iterations: boxes + triangles visited
  uint32_t triangleTests = 0;  // ray/triangle tests performed
};

// Work counters of a divide-and-conquer tracer (DACRT, seed 001's Fig. 8),
// summed over a frame: it has no per-ray traversal, so these say where the
// time goes.
struct FilterStats {
  uint64_t rayBox = 0;        // ray/cell tests while filtering rays
  uint64_t coneBox = 0;       // cone/cell tests while filtering conic packets
  uint64_t triangleBox = 0;   // triangle/cell tests while filtering triangles
  uint64_t rayTriangle = 0;   // ray/triangle tests in the leaves (naive tracing)
  uint64_t nodes = 0;         // cells visited (recursive calls)
  FilterStats& operator+=(const FilterStats& o) {
    rayBox += o.rayBox, coneBox += o.coneBox, triangleBox += o.triangleBox;
    rayTriangle += o.rayTriangle, nodes += o.nodes;
    return *this;
  }
};

}  // namespace passtrace
