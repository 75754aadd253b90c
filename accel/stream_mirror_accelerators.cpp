#include "accel/stream_mirror_accelerators.h"

#include <chrono>

#include "accel/grid/grid_stream_traversal.h"
#include "accel/grid/grid_texels.h"
#include "accel/kd/kd_accelerator.h"
#include "accel/kd/kd_stream_traversal.h"
#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/reference_lists.h"
#include "accel/grid/uniform_grid_builder.h"

namespace passtrace {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

class KdStreamMirror final : public CpuAccelerator {
 public:
  KdStreamMirror(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildKdStream(variant, tris, config)) {
    data_ = KdStreamData{variant, build_.sceneBox, build_.texels.nodes, build_.texels.lists, triangles_,
                         config.triangleTest};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseKdStream(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  KdStreamBuild build_;
  KdStreamData data_;
};

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

KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const KdTree tree = buildKdTree(tris, kdConfigFor(config));
  KdStreamBuild build{variant == KdStreamVariant::Restart ? flattenKdRestart(tree, tris.size())
                                                          : flattenKdBacktrack(tree, tris.size()),
                      tree.bounds, AccelStats{}, 0};
  AccelStats& s = build.stats;
  s.name = variant == KdStreamVariant::Restart ? "kd-restart" : "kd-backtrack";
  s.buildMs = millisecondsSince(start);
  s.floatsPerTriangle = build.texels.floatsPerTriangle;
  s.nodes = tree.nodes.size();
  s.leaves = tree.leafCount();
  s.references = tree.references.size();
  s.depth = tree.depth();
  // Each leaf is searched at most once (plus a re-entry per backtrack), reached through at most depth nodes.
  build.maxStepsPerRay = 2 * (uint64_t(s.leaves) + 1) * (s.depth + 2) + 2 * s.nodes + build.texels.listEntries;
  return build;
}

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

std::optional<StreamMirror> streamMirrorByName(const std::string& name) {
  if (name == "kd-restart") return StreamMirror::KdRestart;
  if (name == "kd-backtrack") return StreamMirror::KdBacktrack;
  if (name == "grid-stream") return StreamMirror::Grid;
  return std::nullopt;
}

std::unique_ptr<CpuAccelerator> makeStreamMirrorAccelerator(StreamMirror which, std::span<const Triangle> tris,
                                                            const AccelBuildConfig& config) {
  switch (which) {
    case StreamMirror::KdRestart: return std::make_unique<KdStreamMirror>(KdStreamVariant::Restart, tris, config);
    case StreamMirror::KdBacktrack: return std::make_unique<KdStreamMirror>(KdStreamVariant::Backtrack, tris, config);
    case StreamMirror::Grid: return std::make_unique<GridStreamMirror>(tris, config);
  }
  return nullptr;
}

}  // namespace passtrace
