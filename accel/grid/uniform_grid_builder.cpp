#include "accel/grid/uniform_grid_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace passtrace {

size_t maxGridCells(size_t triangleCount) { return 128 * triangleCount + 4096; }

glm::ivec3 gridResolution(const Aabb& bounds, size_t triangleCount, float multiplier) {
  if (triangleCount == 0 || bounds.empty()) return glm::ivec3(0);
  const glm::dvec3 extent = glm::dvec3(bounds.extent());
  double shortest = 0.0;
  for (int k = 0; k < 3; ++k)
    if (extent[k] > 0.0 && (shortest == 0.0 || extent[k] < shortest)) shortest = extent[k];
  if (!(shortest > 0.0) || !std::isfinite(shortest)) return glm::ivec3(1);

  const double wanted = std::round(2.0 * std::cbrt(double(triangleCount)) * double(multiplier));
  const double alongShortest = wanted >= 1.0 ? wanted : 1.0;  // also catches NaN and -g <= 0
  double cellEdge = shortest / alongShortest;
  const double cap = double(maxGridCells(triangleCount));
  glm::ivec3 res(1);
  // Each pass grows the edge by the cube root of the excess; axes pinned at
  // one cell make the shrink smaller than that, hence the loop (a few passes).
  for (int pass = 0; pass < 64; ++pass) {
    double cells = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double r = extent[k] > 0.0 ? std::round(extent[k] / cellEdge) : 1.0;
      res[k] = static_cast<int>(std::clamp(r, 1.0, 1048576.0));
      cells *= res[k];
    }
    if (cells <= cap) break;
    cellEdge *= std::cbrt(cells / cap) * 1.0001;
  }
  return res;
}

bool triangleOverlapsBox(const Triangle& tri, const Aabb& box) {
  const glm::vec3 c = box.center();
  const glm::vec3 h = 0.5f * box.extent();
  const glm::vec3 v[3] = {tri.v0 - c, tri.v1 - c, tri.v2 - c};

  // Box face normals: the triangle's bounds against the box.
  for (int k = 0; k < 3; ++k) {
    const float lo = std::min(std::min(v[0][k], v[1][k]), v[2][k]);
    const float hi = std::max(std::max(v[0][k], v[1][k]), v[2][k]);
    if (lo > h[k] || hi < -h[k]) return false;
  }
  // Triangle normal: the box's projection radius against the plane offset.
  const glm::vec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const glm::vec3 n = glm::cross(e[0], e[1]);
  const float radius = h.x * std::fabs(n.x) + h.y * std::fabs(n.y) + h.z * std::fabs(n.z);
  if (std::fabs(glm::dot(n, v[0])) > radius) return false;
  // Cross products of the box axes with the triangle edges.
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 unit(0.0f);
    unit[axis] = 1.0f;
    for (int j = 0; j < 3; ++j) {
      const glm::vec3 a = glm::cross(unit, e[j]);
      const float p0 = glm::dot(a, v[0]), p1 = glm::dot(a, v[1]), p2 = glm::dot(a, v[2]);
      const float r = h.x * std::fabs(a.x) + h.y * std::fabs(a.y) + h.z * std::fabs(a.z);
      if (std::min(std::min(p0, p1), p2) > r || std::max(std::max(p0, p1), p2) < -r) return false;
    }
  }
  return true;
}

glm::vec3 cellPadding(const UniformGrid& grid) {
  if (grid.bounds.empty()) return glm::vec3(0.0f);
  const glm::vec3 magnitude = glm::max(glm::abs(grid.bounds.min), glm::abs(grid.bounds.max));
  const float scale = std::max(std::max(magnitude.x, magnitude.y), magnitude.z);
  return 1e-4f * grid.cellSize + glm::vec3(1e-6f * scale);
}

UniformGrid buildUniformGrid(std::span<const Triangle> tris, const GridConfig& config) {
  UniformGrid grid;
  grid.cellStart = {0};
  if (tris.empty()) return grid;
  for (const Triangle& t : tris) grid.bounds.extend(t.bounds());
  grid.resolution = gridResolution(grid.bounds, tris.size(), config.multiplier);
  grid.cellSize = grid.bounds.extent() / glm::vec3(grid.resolution);
  const glm::vec3 pad = cellPadding(grid);

  // (cell, triangle) pairs in triangle order, then a stable counting sort by
  // cell, so each cell lists its triangles in increasing scene index.
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  pairs.reserve(tris.size() * 2);
  for (uint32_t i = 0; i < tris.size(); ++i) {
    const Triangle& tri = tris[i];
    const Aabb b = tri.bounds();
    // Twice the padding for the range, so rounding in cellOf never drops a
    // cell whose padded box the triangle overlaps.
    const glm::ivec3 lo = grid.cellOf(b.min - 2.0f * pad);
    const glm::ivec3 hi = grid.cellOf(b.max + 2.0f * pad);
    const bool degenerate = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0) == glm::vec3(0.0f);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const glm::ivec3 c(x, y, z);
          Aabb box = grid.cellBox(c);
          box.min -= pad;
          box.max += pad;
          const bool inBounds = glm::all(glm::lessThanEqual(box.min, b.max)) &&
                                glm::all(glm::greaterThanEqual(box.max, b.min));
          if (degenerate ? inBounds : triangleOverlapsBox(tri, box))
            pairs.emplace_back(static_cast<uint32_t>(grid.cellIndex(c)), i);
        }
  }
  const size_t cells = grid.cellCount();
  grid.cellStart.assign(cells + 1, 0);
  for (const auto& p : pairs) ++grid.cellStart[p.first + 1];
  for (size_t c = 0; c < cells; ++c) grid.cellStart[c + 1] += grid.cellStart[c];
  grid.references.resize(pairs.size());
  std::vector<uint32_t> cursor(grid.cellStart.begin(), grid.cellStart.end() - 1);
  for (const auto& p : pairs) grid.references[cursor[p.first]++] = p.second;
  return grid;
}

}  // namespace passtrace
