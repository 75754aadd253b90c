#pragma once
// A uniform grid of voxels ("cells") over the scene bounds (thesis section
// 7), each cell listing the triangles that overlap it, stored compressed:
// the references of cell c are references[cellStart[c], cellStart[c + 1]),
// in increasing scene index.
//
// Geometry of the cells: bounds are the scene bounds exactly; along axis k
// cell i spans [bounds.min + i * cellSize, bounds.min + (i + 1) * cellSize]
// (the last one ending at bounds.max). An axis along which the scene is flat
// has one cell and cellSize 0 there. A point p lies in cell
// clamp(floor((p - bounds.min) / cellSize), 0, resolution - 1), taking 0 on
// axes with one cell (so flat axes never divide by zero).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace {

struct UniformGrid {
  Aabb bounds;                      // the scene bounds; empty for an empty scene
  glm::ivec3 resolution{0};         // cells per axis, each >= 1 (all 0 for an empty scene)
  glm::vec3 cellSize{0.0f};         // extent / resolution; 0 on flat axes
  std::vector<uint32_t> cellStart;  // size cells + 1
  std::vector<uint32_t> references; // scene triangle indices

  size_t cellCount() const { return size_t(resolution.x) * size_t(resolution.y) * size_t(resolution.z); }
  size_t cellIndex(glm::ivec3 c) const { return c.x + size_t(resolution.x) * (c.y + size_t(resolution.y) * c.z); }
  uint32_t referenceCount(size_t cell) const { return cellStart[cell + 1] - cellStart[cell]; }

  // The cell holding p, clamped into the grid (see above).
  glm::ivec3 cellOf(const glm::vec3& p) const {
    glm::ivec3 c(0);
    for (int k = 0; k < 3; ++k) {
      if (resolution[k] <= 1) continue;
      const float f = std::floor((p[k] - bounds.min[k]) / cellSize[k]);
      // Compare as float first: a NaN or huge f must not reach the int cast.
      c[k] = f >= float(resolution[k] - 1) ? resolution[k] - 1 : (f > 0.0f ? int(f) : 0);
    }
    return c;
  }

  // The box of cell c; the last cell along an axis ends exactly at bounds.max.
  Aabb cellBox(glm::ivec3 c) const {
    Aabb box;
    for (int k = 0; k < 3; ++k) {
      box.min[k] = bounds.min[k] + float(c[k]) * cellSize[k];
      box.max[k] = c[k] + 1 >= resolution[k] ? bounds.max[k] : bounds.min[k] + float(c[k] + 1) * cellSize[k];
    }
    return box;
  }
};

}  // namespace passtrace
