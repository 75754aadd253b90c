#include "accel/grid_accelerators.h"

#include <chrono>
#include <stdexcept>
#include <string>

#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/goldsmith_salmon_builder.h"
#include "accel/grid/grid_traversal.h"
#include "accel/octree/octree.h"
#include "accel/grid/uniform_grid.h"
#include "accel/grid/uniform_grid_builder.h"

namespace passtrace {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

GoldsmithSalmonConfig gsConfig(const AccelBuildConfig& config) {
  GoldsmithSalmonConfig gs;
  gs.tries = config.gsTries;
  gs.seed = config.gsSeed;
  return gs;
}

// 4: the uniform grid, 3D-DDA.
class GridAccelerator final : public CpuAccelerator {
public:
  GridAccelerator(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : tris_(tris), test_(config.triangleTest) {
    const auto start = std::chrono::steady_clock::now();
    grid_ = buildUniformGrid(tris, GridConfig{config.gridMultiplier});
    stats_.buildMs = millisecondsSince(start);
    stats_.name = acceleratorName(4);
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

// 7: the octree, front to back.
class OctreeAccelerator final : public CpuAccelerator {
public:
  OctreeAccelerator(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    const auto start = std::chrono::steady_clock::now();
    octree_ = buildOctree(tris);
    stats_.buildMs = millisecondsSince(start);
    stats_.name = acceleratorName(7);
    stats_.nodes = octree_.nodes.size();
    stats_.leaves = octree_.leafCount();
    stats_.references = octree_.references.size();
    stats_.depth = octree_.depth;
    stats_.floatsPerTriangle = octree_.floatsPerTriangle(tris.size());
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseOctree(octree_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  Octree octree_;
  AccelStats stats_;
  TriangleTest test_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeGridFamilyCpuAccelerator(int number, std::span<const Triangle> tris,
                                                             const AccelBuildConfig& config) {
  switch (number) {
    case 1: return makeSequenceAccelerator(buildGoldsmithSalmonSequence(tris, gsConfig(config)), config.triangleTest);
    case 4: return std::make_unique<GridAccelerator>(tris, config);
    case 6: {  // the same tree (same configuration), descended recursively
      const auto start = std::chrono::steady_clock::now();
      Bvh bvh = buildGoldsmithSalmon(tris, gsConfig(config));
      AccelStats stats = bvhStats(6, bvh);
      stats.buildMs = millisecondsSince(start);
      return makeRecursiveBvhAccelerator(tris, std::move(bvh), std::move(stats), config.triangleTest);
    }
    case 7: return std::make_unique<OctreeAccelerator>(tris, config.triangleTest);
    default:
      throw std::invalid_argument("makeGridFamilyCpuAccelerator: accelerator " + std::to_string(number) +
                                  " is not one of 1, 4, 6, 7");
  }
}

}  // namespace passtrace
