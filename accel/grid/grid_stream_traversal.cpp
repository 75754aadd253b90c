#include "accel/grid/grid_stream_traversal.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stream/texel_address.h"

namespace passtrace {
namespace {

float fetchScalar(std::span<const glm::vec4> data, uint32_t index) { return data[index >> 2][int(index & 3u)]; }

uint32_t linearCell(const GridStreamData& d, const glm::ivec3& c) {
  return uint32_t(c.x) + uint32_t(d.resolution.x) * (uint32_t(c.y) + uint32_t(d.resolution.y) * uint32_t(c.z));
}

void advance(const GridStreamData& d, const Ray& ray, GridStreamCursor& c) {
  const float exit = std::min(std::min(c.tNext.x, c.tNext.y), c.tNext.z);
  if (c.best.t <= exit || exit == kInfinity) {
    c.done = true;
    return;
  }
  const int axis = c.tNext.x <= c.tNext.y && c.tNext.x <= c.tNext.z ? 0 : (c.tNext.y <= c.tNext.z ? 1 : 2);
  const glm::vec3 invDir = safeInverse(ray.direction);
  const bool forward = ray.direction[axis] > 0.0f;
  c.cell[axis] += forward ? 1 : -1;
  // Recomputed from the boundary itself, not accumulated, so it never drifts.
  const float boundary = d.gridMin[axis] + float(c.cell[axis] + (forward ? 1 : 0)) * d.cellSize[axis];
  c.tNext[axis] = (boundary - ray.origin[axis]) * invDir[axis];
  c.mode = GridStreamCursor::kModeVisit;
  c.done = c.cell[axis] < 0 || c.cell[axis] >= d.resolution[axis];
}

}  // namespace

GridStreamData makeGridStreamData(const Aabb& bounds, const glm::ivec3& resolution, std::span<const glm::vec4> cells,
                                  std::span<const glm::vec4> lists, std::span<const glm::vec4> triangles) {
  GridStreamData d;
  d.resolution = resolution;
  const glm::vec3 extent = bounds.extent();
  const float thin = 1e-6f * std::max({glm::length(extent), std::fabs(bounds.min.x), std::fabs(bounds.min.y),
                                       std::fabs(bounds.min.z), 1e-30f});
  for (int k = 0; k < 3; ++k) {
    d.cellSize[k] = extent[k] > 0.0f ? extent[k] / float(resolution[k]) : thin;
    d.gridMin[k] = extent[k] > 0.0f ? bounds.min[k] : bounds.min[k] - 0.5f * thin;
  }
  d.invCellSize = 1.0f / d.cellSize;
  d.cells = cells;
  d.lists = lists;
  d.triangles = triangles;
  return d;
}

GridStreamCursor gridStreamStart(const GridStreamData& d, const Ray& ray) {
  GridStreamCursor c;
  c.best.t = ray.tMax;
  const glm::vec3 invDir = safeInverse(ray.direction);
  const Aabb grid{d.gridMin, d.gridMin + glm::vec3(d.resolution) * d.cellSize};
  float tNear, tFar;
  const bool inside = clipToBox(ray.origin, invDir, grid, tNear, tFar);
  const float tMin = std::max(tNear, 0.0f);
  c.done = !(inside && tMin <= std::min(tFar, ray.tMax)) || d.cells.empty();
  const glm::vec3 entry = ray.origin + tMin * ray.direction;
  const glm::vec3 f = glm::floor((entry - d.gridMin) * d.invCellSize);
  for (int k = 0; k < 3; ++k) {
    // Clamp in float first: a far-away entry point must not overflow the int conversion.
    c.cell[k] = int(std::clamp(f[k], 0.0f, float(d.resolution[k] - 1)));
    const float lower = d.gridMin[k] + float(c.cell[k]) * d.cellSize[k];
    const float boundary = ray.direction[k] > 0.0f ? lower + d.cellSize[k] : lower;
    c.tNext[k] = std::fabs(invDir[k]) > kParallelInverse ? kInfinity : (boundary - ray.origin[k]) * invDir[k];
  }
  return c;
}

void gridStreamVisitCell(const GridStreamData& d, const Ray& ray, GridStreamCursor& c) {
  ++c.stats.steps;
  const float start = fetchScalar(d.cells, linearCell(d, c.cell));
  if (start >= 0.0f) c.mode = start;
  else advance(d, ray, c);
}

void gridStreamTestEntry(const GridStreamData& d, const Ray& ray, bool anyHit, GridStreamCursor& c) {
  ++c.stats.steps;
  const uint32_t entry = unpackIndex(c.mode);
  const float id = fetchScalar(d.lists, entry);
  if (id < 0.0f) {
    advance(d, ray, c);
    return;
  }
  ++c.stats.triangleTests;
  const uint32_t t = unpackIndex(id);
  const Triangle tri{glm::vec3(d.triangles[3 * t]), glm::vec3(d.triangles[3 * t + 1]), glm::vec3(d.triangles[3 * t + 2])};
  const bool found = intersectTriangle(ray.origin, ray.direction, tri, t, c.best, d.triangleTest);
  c.done = found && anyHit;
  c.mode = packIndex(entry + 1);
}

bool gridStreamSteps(const GridStreamData& d, const Ray& ray, bool anyHit, GridStreamCursor& c, uint32_t maxSteps) {
  for (uint32_t i = 0; i < maxSteps && !c.done; ++i) {
    if (c.mode < 0.0f) gridStreamVisitCell(d, ray, c);
    else gridStreamTestEntry(d, ray, anyHit, c);
  }
  return !c.done;
}

Hit traverseGridStream(const GridStreamData& d, const Ray& ray, bool anyHit, RayStats* stats) {
  GridStreamCursor c = gridStreamStart(d, ray);
  gridStreamSteps(d, ray, anyHit, c, std::numeric_limits<uint32_t>::max());
  if (stats) {
    stats->steps += c.stats.steps;
    stats->triangleTests += c.stats.triangleTests;
  }
  return c.best;
}

}  // namespace passtrace
