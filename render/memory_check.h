#pragma once
// "Say so before trying": the memory a run will need, estimated from the
// triangle count and the image size before anything is built, against what
// the machine has available. A run that cannot fit ends with one line
// instead of swapping or being killed half-way. Bytes per triangle come from
// the structure's registry row (MemoryModel).

#include <cstdint>
#include <optional>
#include <string>

#include "accel/registry.h"

namespace passtrace {

// Peak resident bytes of a run of `structure` (null for the preview) on
// `renderer` over `triangles` triangles and `pixels` pixels, with a 25 % margin.
// `extraBytesPerPixel`: what the renderer keeps per pixel beyond its base
// (GpuRenderer::extraBytesPerPixel: Whitted stacks, the compaction stream).
uint64_t estimatedRunBytes(RendererId renderer, const Structure* structure, uint64_t triangles, uint64_t pixels,
                           double extraBytesPerPixel = 0);

// MemAvailable from /proc/meminfo, lowered to the cgroup's memory.max less
// its current use where one is set; nullopt when neither can be read.
std::optional<uint64_t> availableMemoryBytes();

// This process's resident bytes now (/proc/self/statm; 0 where unreadable).
uint64_t residentBytes();

// Throws std::runtime_error("SCENE: N triangles with STRUCTURE on the ...
// renderer need about X GiB; Y GiB available (nothing was built)") when the
// estimate exceeds what is available plus what this process holds already
// (the estimate counts the scene, which is loaded before the second check).
void checkRunFitsInMemory(const std::string& scene, RendererId renderer, const Structure* structure,
                          uint64_t triangles, uint64_t pixels, double extraBytesPerPixel = 0);

}  // namespace passtrace
