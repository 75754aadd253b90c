#include "accel/milliseconds_since.h"
#include "accel/octree/octree_structure.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "accel/octree/gpu_octree_traversal.h"
#include "accel/octree/octree.h"
#include "accel/octree/octree_stream_traversal.h"
#include "accel/octree/octree_texels.h"
#include "accel/reference_lists.h"

namespace passtrace {
namespace {

void setOctreeStats(AccelStats& s, const Octree& octree) {
  s.nodes = octree.nodes.size();
  s.leaves = octree.leafCount();
  s.references = octree.references.size();
  s.depth = octree.depth;
}

class OctreeDescent final : public CpuAccelerator {
public:
  OctreeDescent(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    const auto start = std::chrono::steady_clock::now();
    octree_ = buildOctree(tris);
    stats_.buildMs = millisecondsSince(start);
    stats_.name = "octree-descent";
    setOctreeStats(stats_, octree_);
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

struct OctreeStreamBuild {
  OctreeTexels texels;
  Aabb rootBox;
  AccelStats stats;
  uint64_t maxStepsPerRay = 0;
  uint32_t stackSize = 1;
};

OctreeStreamBuild buildOctreeStream(std::span<const Triangle> tris) {
  const auto start = std::chrono::steady_clock::now();
  const Octree octree = buildOctree(tris);
  OctreeStreamBuild b{flattenOctree(octree, tris.size()), octree.nodes.empty() ? Aabb{} : octree.nodes[0].box,
                      AccelStats{}};
  AccelStats& s = b.stats;
  s.buildMs = millisecondsSince(start);
  s.name = "octree";
  setOctreeStats(s, octree);
  s.floatsPerTriangle = b.texels.floatsPerTriangle;
  s.structureBytes = (b.texels.nodes.size() + b.texels.lists.size()) * sizeof(glm::vec4);
  // Each node is reached at most once (one step), each list entry is one step.
  b.maxStepsPerRay = 2 * uint64_t(s.nodes) + b.texels.listEntries + 2;
  // One frame per internal node on the current path.
  b.stackSize = std::max<uint32_t>(1, octree.depth);
  return b;
}

class OctreeRevellesCpu final : public CpuAccelerator {
 public:
  OctreeRevellesCpu(std::span<const Triangle> tris, const AccelBuildConfig& config)
      : triangles_(triangleVertexTexels(tris)), build_(buildOctreeStream(tris)) {
    data_ = OctreeStreamData{build_.rootBox, build_.texels.nodes, build_.texels.lists, triangles_,
                             config.triangleTest};
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseOctreeStream(data_, ray, anyHit, stats);
  }
  std::string name() const override { return build_.stats.name; }
  AccelStats stats() const override { return build_.stats; }

 private:
  std::vector<glm::vec4> triangles_;
  OctreeStreamBuild build_;
  OctreeStreamData data_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeOctreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<OctreeRevellesCpu>(tris, config);
}

std::unique_ptr<GpuTraversal> makeOctreeStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  OctreeStreamBuild b = buildOctreeStream(tris);
  return std::make_unique<GpuOctreeTraversal>(b.texels, b.rootBox, triangleVertexTexels(tris), b.maxStepsPerRay,
                                              b.stackSize, std::move(b.stats), config);
}

std::unique_ptr<CpuAccelerator> makeOctreeDescentCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<OctreeDescent>(tris, config.triangleTest);
}

}  // namespace passtrace
