#include "accel/grid/grid_texels.h"

namespace passtrace {

GridTexels flattenGrid(const UniformGrid& grid, size_t triangleCount) {
  GridTexels out;
  const size_t cells = grid.cellCount();
  out.cells.assign((cells + 3) / 4, glm::vec4(kListEnd));
  ReferenceLists lists;
  for (size_t c = 0; c + 1 < grid.cellStart.size() && c < cells; ++c) {
    const uint32_t begin = grid.cellStart[c], end = grid.cellStart[c + 1];
    if (begin == end) continue;  // stays kListEnd
    const uint32_t start = lists.append(std::span<const uint32_t>(grid.references.data() + begin, end - begin));
    out.cells[c >> 2][int(c & 3)] = packIndex(start);
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  out.floatsPerTriangle =
      triangleCount == 0 ? 0.0 : double(cells + out.listEntries) / double(triangleCount);
  return out;
}

}  // namespace passtrace
