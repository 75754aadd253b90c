#include "accel/grid/grid_structures.h"

#include <chrono>
#include <string>
#include <vector>

#include "accel/grid/gpu_grid_traversal.h"
#include "accel/grid/grid_stream_traversal.h"
#include "accel/grid/grid_traversal.h"
#include "accel/grid/uniform_grid.h"
#include "accel/grid/uniform_grid_builder.h"
#include "accel/milliseconds_since.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

// The uniform grid, 3D-DDA.
class GridAccelerator final : public CpuAccelerator {
public:
  GridAccelerator(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : tris_(tris), test_(config.triangleTest) {
    const auto start = std::chrono::steady_clock::now();
    grid_ = buildUniformGrid(tris, GridConfig{config.gridMultiplier});
    stats_.buildMs = millisecondsSince(start);
    stats_.name = "grid";
    stats_.nodes = grid_.cellCount();
    for (size_t c = 0; c < stats_.nodes; ++c) stats_.leaves += grid_.referenceCount(c) > 0 ? 1 : 0;
    stats_.references = grid_.references.size();
    stats_.depth = tris.empty() ? 0 : 1;
    // flattenGrid's accounting without flattening: one float per cell, and
    // per non-empty cell its references plus a terminator.
    stats_.floatsPerTriangle =
        tris.empty() ? 0.0 : double(stats_.nodes + stats_.references + stats_.leaves) / double(tris.size());
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseGrid(grid_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  UniformGrid grid_;
  AccelStats stats_;
  TriangleTest test_;
};

// The GPU grid kernel's algorithm over its texels, on the CPU.
class GridStreamMirror final : public CpuAccelerator {
 public:
  GridStreamMirror(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildGridStream(tris, config)) {
    build_.stats.name = "grid-stream";
    data_ = makeGridStreamData(build_.bounds, build_.resolution, build_.texels.cells, build_.texels.lists, triangles_);
    data_.triangleTest = config.triangleTest;
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseGridStream(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  GridStreamBuild build_;
  GridStreamData data_;
};

}  // namespace

GridStreamBuild buildGridStream(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const UniformGrid grid = buildUniformGrid(tris, GridConfig{config.gridMultiplier});
  GridStreamBuild build{flattenGrid(grid, tris.size()), grid.bounds, grid.resolution, AccelStats{}, 0};
  AccelStats& s = build.stats;
  s.name = "grid";
  s.buildMs = millisecondsSince(start);
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  s.nodes = grid.cellCount();
  for (size_t c = 0; c < grid.cellCount(); ++c) s.leaves += grid.referenceCount(c) > 0;
  s.references = grid.references.size();
  s.depth = 1;
  // A ray visits at most nx + ny + nz cells and reads each list entry of those once.
  build.maxStepsPerRay =
      uint64_t(grid.resolution.x + grid.resolution.y + grid.resolution.z) + 3 + build.texels.listEntries;
  return build;
}

std::unique_ptr<CpuAccelerator> makeGridCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<GridAccelerator>(tris, config);
}

std::unique_ptr<CpuAccelerator> makeGridStreamMirror(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<GridStreamMirror>(tris, config);
}

std::unique_ptr<GpuTraversal> makeGridStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  GridStreamBuild build = buildGridStream(tris, config.build);
  const GridStreamData data = makeGridStreamData(build.bounds, build.resolution, {}, {}, {});
  return std::make_unique<GpuGridTraversal>(data, build.texels.cells, build.texels.lists, triangleVertexTexels(tris),
                                            build.maxStepsPerRay, std::move(build.stats), config);
}

}  // namespace passtrace
