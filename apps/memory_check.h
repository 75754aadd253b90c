#pragma once
// "Say so before trying": the memory a run will need, estimated from the
// triangle count and the image size before anything is built, against what
// the machine has available. A run that cannot fit ends with one line
// instead of swapping or being killed half-way.

#include <cstdint>
#include <optional>
#include <string>

namespace passtrace {

// Peak resident bytes of a run of `structure` (gpuAcceleratorName(),
// acceleratorName(), a stream-mirror name, "embree" or "preview") on
// `renderer` (-r) over `triangles` triangles and `pixels` pixels: measured
// bytes per triangle (apps/memory_check.cpp) with a 25 % margin.
uint64_t estimatedRunBytes(int renderer, const std::string& structure, uint64_t triangles, uint64_t pixels);

// MemAvailable from /proc/meminfo, lowered to the cgroup's memory.max less
// its current use where one is set; nullopt when neither can be read.
std::optional<uint64_t> availableMemoryBytes();

// Throws std::runtime_error("SCENE: N triangles with STRUCTURE on the ...
// renderer need about X GiB; Y GiB available") when the estimate exceeds
// what is available.
void checkRunFitsInMemory(const std::string& scene, int renderer, const std::string& structure, uint64_t triangles,
                          uint64_t pixels);

}  // namespace passtrace
