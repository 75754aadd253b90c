#pragma once
// Divide-and-conquer ray tracing (Mora 2011, seed 001): no structure is
// stored. Each call splits space recursively and filters the lists of rays
// and triangles into each half, in place (index arrays permuted around
// pivots), until few rays or few triangles remain, which are then tested
// all against all. Algorithm 1 on rays; Algorithm 2 on conic packets.

#include <optional>
#include <span>

#include "accel/cpu_accelerator.h"

namespace passtrace::dacrt {

struct Settings {
  int rLimit = 20;   // trace naively at this many rays or fewer ...
  int pLimit = 16;   // ... or this many triangles or fewer
  bool cones = false;
  bool medianSplit = false;  // always the spatial median (else the seed's sampled mean above 10,000 triangles)
  TriangleTest test = TriangleTest::MollerTrumbore;
};

// Traces a batch: hits[i] gets the closest hit of ray i before its tMax
// (ties to the lowest triangle index, as brute force), or for a shadow ray
// some hit before tMax; {tMax, kNoHit} when none. stats[i] is added to: a
// step per cell the ray is tested against, and its triangle tests. Returns
// the frame's filter counters.
FilterStats trace(std::span<const Triangle> tris, const Settings& settings, const RayBatch& batch,
                  std::span<Hit> hits, std::span<RayStats> stats);

}  // namespace passtrace::dacrt
