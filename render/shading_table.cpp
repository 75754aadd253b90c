#include "render/shading_table.h"

#include "render/parallel_for.h"

namespace passtrace {

std::vector<ShadingEntry> makeShadingTable(const Scene& scene, unsigned threads) {
  std::vector<ShadingEntry> table(scene.triangles.size());
  parallelFor(table.size(), 16384, threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      // A hand-made scene may lack material ids; shading would not read them unless hit.
      table[i] = ShadingEntry{glm::normalize(scene.triangles[i].geometricNormal()),
                              i < scene.materialIds.size() ? scene.materialIds[i] : 0u};
  });
  return table;
}

}  // namespace passtrace
