#pragma once
// The uniform-grid traversal on the CPU step for step as
// kernels_glsl/grid/grid_traversal.glsl runs it on the GPU (3D-DDA, one cell visit
// or one list entry per step), over the same texels (accel/grid/grid_texels.h):
// for debugging the kernels, which must find the same hits and count the
// same steps.
//
// Why a copy and not one source: the kernel resumes across passes (its state
// packed into RGBA32F surfaces, at most -l steps per pass, the stack-free
// formulation the thesis needs), the mirror runs each ray to completion; a
// GLSL-compatible C++ subset shared by both would need macros for texel
// fetches, `precise` and the pass structure, and hide the very loop a reader
// compares with the thesis. The copy is held to the kernel instead:
// tests/gpu_traversal_test.cpp checks, for every registry row with a stream
// kernel, the same hits and the same step and triangle-test counts per ray.

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct GridStreamData {
  glm::vec3 gridMin{0.0f}, cellSize{1.0f}, invCellSize{1.0f};
  glm::ivec3 resolution{1};
  std::span<const glm::vec4> cells, lists, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;  // as the kernels are compiled
};

// The stream view of a grid spanning `bounds` with `resolution` cells. A flat
// axis (zero extent) gets a thin slab of positive size around its plane, so
// cell lookups never divide by zero.
GridStreamData makeGridStreamData(const Aabb& bounds, const glm::ivec3& resolution, std::span<const glm::vec4> cells,
                                  std::span<const glm::vec4> lists, std::span<const glm::vec4> triangles);

struct GridStreamCursor {
  static constexpr float kModeVisit = -1.0f;
  glm::ivec3 cell{0};
  glm::vec3 tNext{0.0f};
  float mode = kModeVisit;  // kModeVisit or a packed list entry
  Hit best;
  RayStats stats;
  bool done = false;
};

// grid_init.frag: the first cell and boundary crossings; done if the ray misses the grid.
GridStreamCursor gridStreamStart(const GridStreamData& data, const Ray& ray);
// One cell visit (grid_split_step.frag) or one list entry (grid_split_intersect.frag).
void gridStreamVisitCell(const GridStreamData& data, const Ray& ray, GridStreamCursor& cursor);
void gridStreamTestEntry(const GridStreamData& data, const Ray& ray, bool anyHit, GridStreamCursor& cursor);
// Up to maxSteps steps of grid_traverse.frag; returns true while work remains.
bool gridStreamSteps(const GridStreamData& data, const Ray& ray, bool anyHit, GridStreamCursor& cursor,
                     uint32_t maxSteps);
Hit traverseGridStream(const GridStreamData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
