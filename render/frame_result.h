#pragma once
// What one rendered frame hands back, whichever renderer made it.

#include <cstdint>
#include <optional>
#include <vector>

#include "accel/geometry/geometry.h"
#include "accel/traversal_stats.h"
#include "render/image_output.h"

namespace passtrace {

struct FrameStats {
  uint64_t rays = 0;           // all rays traced: primary, shadow and reflection
  uint64_t passes = 0;         // traversal passes (GPU); bounces traced (CPU)
  uint64_t steps = 0;          // traversal steps of all rays
  uint64_t triangleTests = 0;  // triangle tests of all rays
  // The most of any one pixel (stream element) over all its rays in the frame
  // (its primary ray and the shadow and reflection rays that follow it; with
  // -b 1 exactly its primary ray): the same counts the heat map shows.
  uint64_t maxStepsPerRay = 0;
  uint64_t maxTriangleTestsPerRay = 0;
  double frameMs = 0;          // ray generation through the last shading pass
  std::optional<FilterStats> filter;  // batch tracers' (DACRT's) counters, all bounces
};

struct FrameResult {
  int width = 0, height = 0;
  std::vector<float> rgb;                // width*height*3, row 0 the top row
  std::vector<HitRecord> primaryHits;    // filled when asked for
  std::vector<float> steps;              // per pixel: traversal steps of all its rays
  FrameStats stats;
};

// A miss in hit records: id 4294967295 with t = +inf.
inline HitRecord hitRecordOf(const Hit& hit) {
  return hit.found() ? HitRecord{hit.t, hit.u, hit.v, hit.id} : HitRecord{kInfinity, 0.0f, 0.0f, kNoHit};
}

}  // namespace passtrace
