#include "accel/grid/grid_traversal.h"

namespace passtrace {

Hit traverseGrid(const UniformGrid& grid, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                 RayStats* stats, TriangleTest test) {
  Hit best{ray.tMax};
  if (grid.cellCount() == 0) return best;
  const glm::vec3 invDir = safeInverse(ray.direction);
  float tNear, tFar;
  if (!clipRayToBox(ray.origin, invDir, grid.bounds, best.t, tNear, tFar)) return best;
  const float tStart = std::max(tNear, 0.0f);
  glm::ivec3 cell = grid.cellOf(ray.origin + tStart * ray.direction);

  // Per axis: the step (0 = never leave this cell column) and which boundary
  // of the current cell the ray crosses next.
  glm::ivec3 step(0);
  for (int k = 0; k < 3; ++k)
    if (grid.resolution[k] > 1 && std::fabs(invDir[k]) <= kParallelInverse) step[k] = ray.direction[k] > 0.0f ? 1 : -1;
  auto nextBoundary = [&](int k) {
    if (step[k] == 0) return kInfinity;
    const int boundary = cell[k] + (step[k] > 0 ? 1 : 0);
    return (grid.bounds.min[k] + float(boundary) * grid.cellSize[k] - ray.origin[k]) * invDir[k];
  };
  glm::vec3 tNext(nextBoundary(0), nextBoundary(1), nextBoundary(2));

  uint32_t steps = 0, tests = 0;
  for (;;) {
    ++steps;
    const size_t c = grid.cellIndex(cell);
    bool stop = false;
    for (uint32_t r = grid.cellStart[c]; r < grid.cellStart[c + 1]; ++r) {
      const uint32_t id = grid.references[r];
      ++tests;
      if (intersectTriangle(ray.origin, ray.direction, tris[id], id, best, test) && anyHit) {
        stop = true;
        break;
      }
    }
    if (stop) break;
    const int axis = tNext.x <= tNext.y ? (tNext.x <= tNext.z ? 0 : 2) : (tNext.y <= tNext.z ? 1 : 2);
    const float exitT = std::min(tNext[axis], tFar);
    if (best.t <= exitT || tNext[axis] >= tFar) break;  // hit inside this cell, or leaving the grid
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= grid.resolution[axis]) break;
    tNext[axis] = nextBoundary(axis);
  }
  if (stats) {
    stats->steps += steps;
    stats->triangleTests += tests;
  }
  return best;
}

}  // namespace passtrace
