#pragma once
// What shading reads of a hit triangle, 16 bytes per triangle in one array:
// its unit geometric normal and its material index. Shading a hit otherwise
// loads the 36-byte triangle and the separate material-id array, two cache
// misses per hit into arrays the traversal does not share (perf: about half of
// the CPU renderer's shading time on bunny was these loads).

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace passtrace {

struct ShadingEntry {
  // normalize(tri.geometricNormal()), computed exactly as shading did from the
  // triangle, so the shade stays bit-identical.
  glm::vec3 normal{0.0f};
  uint32_t material = 0;  // scene.materialIds[triangle]
};
static_assert(sizeof(ShadingEntry) == 16);

// One entry per scene triangle, in scene order, built on `threads` threads (0: all cores).
std::vector<ShadingEntry> makeShadingTable(const Scene& scene, unsigned threads = 0);

}  // namespace passtrace
