#pragma once
// The uniform grid as the GPU reads it (thesis 7.4, figures 11 and 12). The
// GLSL is written against exactly this layout:
//
//   cells: one float per cell, four cells per RGBA texel, cell c (the
//     UniformGrid::cellIndex order, x fastest) in channel c & 3 of texel
//     c >> 2: packIndex(entry index of the cell's list in `lists`), or
//     kListEnd (-1) for an empty cell. Padding channels are kListEnd.
//   lists: ReferenceLists::texels() (accel/reference_lists.h): per non-empty
//     cell, in cell order, its triangles' packed scene indices in increasing
//     order, then kListEnd; entry j in channel j & 3 of texel j >> 2.
//
// The triangles themselves are triangleVertexTexels() of the scene, and the
// grid's bounds, resolution and cellSize travel as uniforms.

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "accel/reference_lists.h"
#include "accel/grid/uniform_grid.h"

namespace passtrace {

struct GridTexels {
  std::vector<glm::vec4> cells;
  std::vector<glm::vec4> lists;
  size_t listEntries = 0;  // entries in lists before padding: references + non-empty cells
  // Thesis Table 3 accounting (triangles excluded): one float per cell and
  // one per list entry, (cellCount + listEntries) / triangleCount; 0 when
  // there are no triangles.
  double floatsPerTriangle = 0;
};

// triangleCount is the scene's (the denominator of floatsPerTriangle).
GridTexels flattenGrid(const UniformGrid& grid, size_t triangleCount);

}  // namespace passtrace
