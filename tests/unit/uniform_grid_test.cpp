// The uniform grid (CPU structure grid; its texels feed the GPU grid
// kernels): the resolution rule, every cell listing exactly the triangles
// overlapping it (boundary and degenerate ones included), the texel layout
// the kernels read, and the 3D-DDA's cell order.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/grid/grid_texels.h"
#include "accel/grid/grid_traversal.h"
#include "accel/grid/uniform_grid.h"
#include "accel/grid/uniform_grid_builder.h"
#include "accel/reference_lists.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::cellBoundaryMesh;
using testmesh::NamedMesh;

class UniformGridMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(UniformGridMeshTest, GridListsEveryCellTheTriangleOverlaps) {
  const auto& tris = GetParam().tris;
  const UniformGrid grid = buildUniformGrid(tris);
  ASSERT_EQ(grid.cellStart.size(), grid.cellCount() + 1);
  ASSERT_EQ(grid.cellStart.back(), grid.references.size());
  const glm::vec3 pad = cellPadding(grid);
  size_t checked = 0;
  // Brute force over all (cell, triangle) pairs; the big meshes are sampled.
  const size_t stride = std::max<size_t>(1, grid.cellCount() * tris.size() / 4'000'000);
  for (size_t c = 0; c < grid.cellCount(); c += stride) {
    const glm::ivec3 cell(int(c % grid.resolution.x), int(c / grid.resolution.x % grid.resolution.y),
                          int(c / (size_t(grid.resolution.x) * grid.resolution.y)));
    ASSERT_EQ(grid.cellIndex(cell), c);
    const std::set<uint32_t> listed(grid.references.begin() + grid.cellStart[c],
                                    grid.references.begin() + grid.cellStart[c + 1]);
    EXPECT_TRUE(std::is_sorted(grid.references.begin() + grid.cellStart[c], grid.references.begin() + grid.cellStart[c + 1]));
    EXPECT_EQ(listed.size(), grid.referenceCount(c)) << "a triangle listed twice in one cell";
    const Aabb exact = grid.cellBox(cell);
    const Aabb padded{exact.min - pad, exact.max + pad};
    for (uint32_t t = 0; t < tris.size(); ++t) {
      ++checked;
      const bool degenerate = glm::cross(tris[t].v1 - tris[t].v0, tris[t].v2 - tris[t].v0) == glm::vec3(0.0f);
      const Aabb b = tris[t].bounds();
      const bool touchesPadded = glm::all(glm::lessThanEqual(padded.min, b.max)) &&
                                 glm::all(glm::greaterThanEqual(padded.max, b.min));
      if (triangleOverlapsBox(tris[t], exact)) {
        EXPECT_TRUE(listed.count(t)) << "cell " << c << " misses triangle " << t;
      }
      if (listed.count(t)) {
        EXPECT_TRUE(degenerate ? touchesPadded : triangleOverlapsBox(tris[t], padded))
            << "cell " << c << " lists triangle " << t << " that does not overlap it";
      }
    }
  }
  EXPECT_GT(checked, 0u);
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, UniformGridMeshTest, ::testing::ValuesIn(testmesh::standardMeshesAndCellBoundaries()), meshName);

// --- uniform grid -----------------------------------------------------------------

TEST(UniformGrid, ResolutionFollowsTheShortestAxis) {
  // A 2 x 1 x 1 box and 1000 triangles: 2 cbrt(1000) = 20 along y and z, 40 along x.
  const Aabb box{glm::vec3(0), glm::vec3(2, 1, 1)};
  EXPECT_EQ(gridResolution(box, 1000), glm::ivec3(40, 20, 20));
  EXPECT_EQ(gridResolution(box, 1000, 0.5f), glm::ivec3(20, 10, 10));
  EXPECT_EQ(gridResolution(box, 1000, 1.5f), glm::ivec3(60, 30, 30));
  // The shortest axis may be any of them; 8 triangles give 4 along it.
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(0), glm::vec3(3, 6, 1)}, 8), glm::ivec3(12, 24, 4));
  // Flat axes get one cell; the shortest non-flat axis sets the edge.
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(0), glm::vec3(2, 1, 0)}, 1000), glm::ivec3(40, 20, 1));
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(1), glm::vec3(1)}, 1000), glm::ivec3(1));
  EXPECT_EQ(gridResolution(box, 1, 0.01f), glm::ivec3(2, 1, 1)) << "at least one cell";
  EXPECT_EQ(gridResolution(box, 0), glm::ivec3(0));
  // A needle: the rule would ask for 20 x 2e6 x 20 cells; the cap holds.
  const glm::ivec3 needle = gridResolution(Aabb{glm::vec3(0), glm::vec3(1e-4f, 10.0f, 1e-4f)}, 1000);
  EXPECT_LE(double(needle.x) * needle.y * needle.z, double(maxGridCells(1000)));
  EXPECT_GE(needle.y, 1000);
  // Built grids use the rule: the boundary mesh has exactly 8^3 unit cells.
  const UniformGrid grid = buildUniformGrid(cellBoundaryMesh());
  EXPECT_EQ(grid.resolution, glm::ivec3(8));
  EXPECT_EQ(grid.cellSize, glm::vec3(1.0f));
  EXPECT_EQ(buildUniformGrid(cellBoundaryMesh(), {.multiplier = 0.5f}).resolution, glm::ivec3(4));
}

TEST(UniformGrid, BoundaryTrianglesGoToBothCells) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  // Triangle 26 lies in the plane z = 4, between cell layers 3 and 4.
  auto listed = [&](glm::ivec3 c, uint32_t t) {
    const size_t i = grid.cellIndex(c);
    return std::count(grid.references.begin() + grid.cellStart[i], grid.references.begin() + grid.cellStart[i + 1], t) == 1;
  };
  EXPECT_TRUE(listed({6, 2, 3}, 26));
  EXPECT_TRUE(listed({6, 2, 4}, 26));
  EXPECT_FALSE(listed({6, 2, 5}, 26));
  // Triangle 0 lies in x = 0 (the grid's min face) over y 1..4, z 2..6.
  EXPECT_TRUE(listed({0, 1, 2}, 0));
  EXPECT_FALSE(listed({1, 1, 2}, 0));
}

TEST(UniformGrid, DegenerateTrianglesAreListedByTheirBounds) {
  std::vector<Triangle> tris = testmesh::singleTriangle();  // z = 0, x, y in [-1, 1]
  tris.push_back({glm::vec3(0.1f, 0.1f, 0.0f), glm::vec3(0.1f, 0.1f, 0.0f), glm::vec3(0.1f, 0.1f, 0.0f)});
  tris.push_back({glm::vec3(-0.9f, -0.9f, 0.0f), glm::vec3(0.9f, 0.9f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0f)});
  const UniformGrid grid = buildUniformGrid(tris);
  EXPECT_EQ(grid.resolution.z, 1);
  size_t pointRefs = 0, lineRefs = 0;
  for (uint32_t r : grid.references) {
    pointRefs += r == 1;
    lineRefs += r == 2;
  }
  EXPECT_GE(pointRefs, 1u);
  EXPECT_GE(lineRefs, size_t(grid.resolution.x));
  const auto none = buildUniformGrid(testmesh::pointMesh(100));
  EXPECT_EQ(none.resolution, glm::ivec3(1));
  EXPECT_EQ(none.references.size(), 100u);
  EXPECT_FALSE(traverseGrid(none, testmesh::pointMesh(100), Ray{glm::vec3(0.5f, 0.5f, -1), glm::vec3(0, 0, 1)}, false).found());
}

TEST(UniformGrid, FlattenLayoutIsWhatTheKernelReads) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  const GridTexels texels = flattenGrid(grid, tris.size());
  ASSERT_EQ(texels.cells.size(), (grid.cellCount() + 3) / 4);
  size_t nonEmpty = 0;
  std::vector<float> entries(texels.lists.size() * 4);
  for (size_t j = 0; j < entries.size(); ++j) entries[j] = texels.lists[j >> 2][int(j & 3)];
  for (size_t c = 0; c < grid.cellCount(); ++c) {
    const float start = texels.cells[c >> 2][int(c & 3)];
    if (grid.referenceCount(c) == 0) {
      EXPECT_EQ(start, kListEnd) << "cell " << c;
      continue;
    }
    ++nonEmpty;
    ASSERT_GE(start, 0.0f);
    uint32_t j = unpackIndex(start);
    for (uint32_t r = grid.cellStart[c]; r < grid.cellStart[c + 1]; ++r, ++j) {
      ASSERT_LT(j, entries.size());
      EXPECT_EQ(unpackIndex(entries[j]), grid.references[r]);
    }
    EXPECT_EQ(entries[j], kListEnd);
  }
  for (size_t c = grid.cellCount(); c < 4 * texels.cells.size(); ++c) EXPECT_EQ(texels.cells[c >> 2][int(c & 3)], kListEnd);
  EXPECT_EQ(texels.listEntries, grid.references.size() + nonEmpty);
  EXPECT_EQ(texels.lists.size(), (texels.listEntries + 3) / 4);
  EXPECT_DOUBLE_EQ(texels.floatsPerTriangle, double(grid.cellCount() + texels.listEntries) / double(tris.size()));
  // The accelerator reports the same numbers without flattening.
  const AccelStats s = testing_registry::cpuStructure(4, tris)->stats();
  EXPECT_EQ(s.name, "grid");
  EXPECT_EQ(s.nodes, grid.cellCount());
  EXPECT_EQ(s.leaves, nonEmpty);
  EXPECT_EQ(s.references, grid.references.size());
  EXPECT_EQ(s.depth, 1u);
  EXPECT_DOUBLE_EQ(s.floatsPerTriangle, texels.floatsPerTriangle);
  // An empty grid flattens to nothing.
  const GridTexels empty = flattenGrid(buildUniformGrid({}), 0);
  EXPECT_TRUE(empty.cells.empty());
  EXPECT_EQ(empty.floatsPerTriangle, 0.0);
}

TEST(UniformGrid, TraversalVisitsCellsInOrderAndStopsAtTheFirstHitCell) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  // Down the +x axis through the middle of row (y, z) = (6.5, 7.5): nothing
  // there but the big triangles; all 8 cells of the row without a hit, or
  // fewer when one is hit.
  RayStats stats;
  const Ray ray{glm::vec3(-1.0f, 0.5f, 7.5f), glm::vec3(1, 0, 0)};
  const Hit h = traverseGrid(grid, tris, ray, false, &stats);
  const Hit b = intersectBruteForce(tris, ray, false);
  EXPECT_EQ(h.id, b.id);
  EXPECT_LE(stats.steps, 8u);
  // A ray starting inside, exactly on a cell corner, parallel to two axes.
  const Ray corner{glm::vec3(3.0f, 3.0f, 3.0f), glm::vec3(0, 0, 1)};
  EXPECT_EQ(traverseGrid(grid, tris, corner, false).id, intersectBruteForce(tris, corner, false).id);
  // Missing the grid entirely costs nothing.
  RayStats none;
  EXPECT_FALSE(traverseGrid(grid, tris, Ray{glm::vec3(-1), glm::vec3(-1, 0, 0)}, false, &none).found());
  EXPECT_EQ(none.steps, 0u);
}

}  // namespace
}  // namespace passtrace
