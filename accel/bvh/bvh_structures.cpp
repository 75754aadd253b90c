#include "accel/bvh/bvh_structures.h"

#include <chrono>

#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/goldsmith_salmon_builder.h"
#include "accel/bvh/gpu_bvh_traversal.h"
#include "accel/bvh/gpu_octant_bvh_traversal.h"
#include "accel/bvh/octant_sequences.h"
#include "accel/bvh_stack/bvh_stack_structure.h"
#include "accel/milliseconds_since.h"
#include "accel/return_freed_memory.h"

namespace passtrace {
namespace {

GoldsmithSalmonConfig gsConfig(const AccelBuildConfig& config) { return {config.gsTries, config.gsSeed}; }

// A BVH's escape-index sequence, traversed as the GPU does. Keeps only the
// sequence, which carries its own copy of the vertices.
class SequenceAccelerator final : public CpuAccelerator {
public:
  SequenceAccelerator(SequenceBuild build, TriangleTest test)
      : sequence_(std::move(build.sequence)), stats_(std::move(build.stats)), test_(test) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseEscapeSequence(sequence_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  EscapeSequence sequence_;
  AccelStats stats_;
  TriangleTest test_;
};

// The same kind of tree descended recursively; holds the caller's triangles.
class RecursiveBvhAccelerator final : public CpuAccelerator {
public:
  RecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats, TriangleTest test)
      : tris_(tris), bvh_(std::move(bvh)), stats_(std::move(stats)), test_(test) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseBvhRecursive(bvh_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  Bvh bvh_;
  AccelStats stats_;
  TriangleTest test_;
};

SequenceBuild buildGsSequence(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  SequenceBuild build = buildGoldsmithSalmonSequence(tris, gsConfig(config));
  build.stats.name = "gs-bvh";
  return build;
}

std::unique_ptr<CpuAccelerator> recursive(const std::string& name, std::span<const Triangle> tris, Bvh (*buildTree)(std::span<const Triangle>, const AccelBuildConfig&),
                                          const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh = buildTree(tris, config);
  AccelStats stats = bvhStats(name, bvh);
  stats.buildMs = millisecondsSince(start);
  return makeRecursiveBvhAccelerator(tris, std::move(bvh), std::move(stats), config.triangleTest);
}

// The octant-ordered sequences, each ray walking its own octant's as the GPU does.
class OctantSequenceAccelerator final : public CpuAccelerator {
public:
  OctantSequenceAccelerator(OctantSequences sequences, AccelStats stats, TriangleTest test)
      : sequences_(std::move(sequences)), stats_(std::move(stats)), test_(test) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseEscapeSequence(sequences_.sequence(rayOctant(ray.direction)), ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  OctantSequences sequences_;
  AccelStats stats_;
  TriangleTest test_;
};

// bvh-octant's tree and its statistics; the CPU row keeps its eight
// sequences in memory, the stream rows write them into their texture.
struct OctantTree {
  Bvh bvh;
  AccelStats stats;
};

OctantTree buildOctantTree(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  // bvh-stack's builder, but with leaves of one triangle allowed: the walk
  // spends a whole step (three texels) on each triangle of a leaf, so the SAH
  // decides every leaf rather than stopping at four. Measured on the stream
  // path: triangle tests per ray 7.4 -> 3.1 (Kitchen), 9.3 -> 3.6 (Robots),
  // 1.26 -> 0.77 (bunny); bvh-octant-fused 3-17 % more rays per second
  // (docs/bench-speed/NOTES.md, eleventh session).
  BvhStackConfig constants;
  constants.leafSize = 1;
  const BinaryBvh binary = buildBvhStackTree(tris, config.bvhBuilder, constants);
  OctantTree tree{bvhFromBinaryBvh(binary, tris), {}};
  tree.stats = bvhStats("bvh-octant", tree.bvh);
  tree.stats.sahCost = binaryBvhSahCost(binary, constants.traversalCost, constants.intersectionCost);
  return tree;
}

// The build's statistics once sequence 0 is flattened: Table 3's accounting
// (floats per box, triangles excluded) for the eight; their bytes and the
// shared triangle stream's.
void finishOctantStats(AccelStats& stats, std::chrono::steady_clock::time_point start, const OctantZero& zero) {
  stats.buildMs = millisecondsSince(start);
  stats.floatsPerTriangle = kOctants * zero.sequence.floatsPerTriangle();
  stats.structureBytes = (kOctants * zero.sequence.texels.size() + zero.triangles.size()) * sizeof(glm::vec4);
}


Bvh kkTree(std::span<const Triangle> tris, const AccelBuildConfig& config) { return buildKayKajiya(tris, config.kayKajiya); }
Bvh gsTree(std::span<const Triangle> tris, const AccelBuildConfig& config) { return buildGoldsmithSalmon(tris, gsConfig(config)); }

}  // namespace

AccelStats bvhStats(const std::string& name, const Bvh& bvh) {
  AccelStats s;
  s.name = name;
  s.nodes = bvh.nodes.size();
  s.leaves = bvh.leafCount();
  s.references = s.leaves;
  s.depth = bvh.depth();
  s.floatsPerTriangle = s.leaves == 0 ? 0.0 : 8.0 * static_cast<double>(s.nodes - s.leaves) / static_cast<double>(s.leaves);
  return s;
}

SequenceBuild buildKayKajiyaSequence(std::span<const Triangle> tris, const KayKajiyaConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildKayKajiya(tris, config);
  SequenceBuild build{flattenEscapeSequence(bvh, tris), bvhStats("kk-bvh", bvh)};
  build.stats.buildMs = millisecondsSince(start);
  build.stats.floatsPerTriangle = build.sequence.floatsPerTriangle();
  return build;
}

std::unique_ptr<CpuAccelerator> makeSequenceAccelerator(SequenceBuild build, TriangleTest test) {
  return std::make_unique<SequenceAccelerator>(std::move(build), test);
}

std::unique_ptr<CpuAccelerator> makeRecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats,
                                                            TriangleTest test) {
  return std::make_unique<RecursiveBvhAccelerator>(tris, std::move(bvh), std::move(stats), test);
}

std::unique_ptr<CpuAccelerator> makeKkBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return makeSequenceAccelerator(buildKayKajiyaSequence(tris, config.kayKajiya), config.triangleTest);
}

std::unique_ptr<CpuAccelerator> makeGsBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return makeSequenceAccelerator(buildGsSequence(tris, config), config.triangleTest);
}

std::unique_ptr<CpuAccelerator> makeKkBvhRecursiveCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return recursive("kk-bvh-recursive", tris, kkTree, config);
}

std::unique_ptr<CpuAccelerator> makeGsBvhRecursiveCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return recursive("gs-bvh-recursive", tris, gsTree, config);
}

std::unique_ptr<GpuTraversal> makeKkBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  SequenceBuild build = buildKayKajiyaSequence(tris, config.build.kayKajiya);
  return std::make_unique<GpuBvhTraversal>(build.sequence, std::move(build.stats), config);
}

std::unique_ptr<GpuTraversal> makeGsBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  SequenceBuild build = buildGsSequence(tris, config.build);
  return std::make_unique<GpuBvhTraversal>(build.sequence, std::move(build.stats), config);
}

std::unique_ptr<CpuAccelerator> makeOctantBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  OctantTree tree = buildOctantTree(tris, config);
  OctantZero zero = flattenOctantZero(tree.bvh, tris);
  finishOctantStats(tree.stats, start, zero);
  OctantSequences sequences = octantSequencesFrom(std::move(zero), tris);
  tree.stats.buildMs = millisecondsSince(start);
  return std::make_unique<OctantSequenceAccelerator>(std::move(sequences), std::move(tree.stats), config.triangleTest);
}

// bvh-octant and bvh-octant-fused on the stream path: sequence 0 flattened
// and the tree freed before the eight are written into their texture (the
// peak memory is that texture beside sequence 0).
std::unique_ptr<GpuTraversal> makeOctantStream(std::span<const Triangle> tris, const GpuTraversalConfig& config,
                                               GpuOctantBvhTraversal::Fused fused) {
  const auto start = std::chrono::steady_clock::now();
  OctantZero zero;
  AccelStats stats;
  {
    OctantTree tree = buildOctantTree(tris, config.build);
    zero = flattenOctantZero(tree.bvh, tris);
    stats = std::move(tree.stats);
  }
  returnFreedMemory();  // the tree and the builder's temporaries, before the texture's pages
  finishOctantStats(stats, start, zero);
  if (fused == GpuOctantBvhTraversal::Fused::Yes) stats.name = "bvh-octant-fused";
  return std::make_unique<GpuOctantBvhTraversal>(std::move(zero), tris, std::move(stats), config, fused);
}

std::unique_ptr<GpuTraversal> makeOctantBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config) {
  return makeOctantStream(tris, config, GpuOctantBvhTraversal::Fused::No);
}

std::unique_ptr<GpuTraversal> makeOctantBvhFusedStream(std::span<const Triangle> tris,
                                                       const GpuTraversalConfig& config) {
  return makeOctantStream(tris, config, GpuOctantBvhTraversal::Fused::Yes);
}

}  // namespace passtrace
