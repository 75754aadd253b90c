#pragma once
// Uniform grid construction (thesis 7.1 and 11.2): the resolution rule and
// the exact triangle/cell overlap test that fills the cells.

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/grid/uniform_grid.h"

namespace passtrace {

struct GridConfig {
  // tracy's -g: scales the resolution on every axis (2 doubles it, 0.5
  // halves it); 1 keeps the heuristic 2 * cbrt(N) of thesis 11.2.
  float multiplier = 1.0f;
};

// Most cells a grid over n triangles may have: 128 n + 4096. The thesis's
// hand-tuned grids (11.2: Robots 116x189x242 with -g 1.4, Kitchen 246x123x248
// with -g 1.3) use about 70 cells per triangle, so the cap leaves room for
// them and for -g a little above, yet keeps a very thin scene (where the
// shortest-axis rule would give millions of cells along the long axes) or
// an extreme -g from exhausting memory.
size_t maxGridCells(size_t triangleCount);

// Cells per axis for a scene with these bounds and triangle count:
// round(2 * cbrt(n) * multiplier) cells (at least 1) along the shortest axis
// of non-zero extent, and round(extent / cellEdge) (at least 1) along the
// others, so cells are near cubic. Axes of zero extent get 1 cell; so do all
// axes of a point-like scene. When the product exceeds maxGridCells(n), the
// cell edge is grown until it does not (axes already at 1 stay there).
// An empty box or n = 0 gives (0, 0, 0).
glm::ivec3 gridResolution(const Aabb& bounds, size_t triangleCount, float multiplier = 1.0f);

// Akenine-Möller's separating-axis triangle/box overlap test (13 axes: the
// box faces, the triangle normal, the 9 edge cross products). Touching
// counts as overlapping. Handles degenerate triangles: a segment or point is
// tested as such (its zero axes separate nothing).
bool triangleOverlapsBox(const Triangle& tri, const Aabb& box);

// The cell box grown by this much on every side before the overlap test, so
// a triangle on (or within rounding of) a cell boundary is listed in both
// cells and a traversal that rounds the other way still finds it:
// 1e-4 of the cell's edge plus 1e-6 of the largest coordinate magnitude.
glm::vec3 cellPadding(const UniformGrid& grid);

// Builds the grid: every triangle is listed in every cell whose padded box
// it overlaps (triangleOverlapsBox), examining only the cells within its
// padded bounds; a zero-area triangle (never hit, but kept listed) goes to
// every cell its padded bounds touch. An empty span gives an empty grid with
// cellStart = {0}. O(N + cells + references) time and memory.
UniformGrid buildUniformGrid(std::span<const Triangle> tris, const GridConfig& config = {});

}  // namespace passtrace
