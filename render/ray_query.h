#pragma once
// Tracing rays the caller made (not a camera's) through a structure: the
// Python module's Accelerator.intersect / occluded, and the tests that trace
// hand-made rays. The CPU path is here; the GPU stream path is
// render/stream_ray_query.h. Per-ray counters are the heat map's: traversal
// steps and triangle tests.
#include <span>
#include "accel/cpu_accelerator.h"

namespace passtrace {

// Traces rays[i] into hits[i] (closest hit, or with anyHit any hit before
// tMax) on `threads` threads (0: all cores). stats, when not empty, has one
// entry per ray and is overwritten. Each structure traces as the CPU renderer
// has it trace: batch tracers (DACRT) get every ray at once, packet tracers
// (bvh8-packet, Embree) packets of consecutive rays, the others one ray at a
// time.
void traceRays(const CpuAccelerator& structure, std::span<const Ray> rays, bool anyHit, std::span<Hit> hits,
               std::span<RayStats> stats, unsigned threads = 0);

}  // namespace passtrace
