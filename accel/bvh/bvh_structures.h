#pragma once
// The BVH family's registry entries: the Kay/Kajiya (K/K) and
// Goldsmith/Salmon (G/S) trees, each walked as its escape-index sequence
// (CPU and GPU stream alike, thesis 9.3) or descended recursively (CPU).

#include <memory>
#include <span>
#include <string>

#include "accel/bvh/bvh.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

// A BVH flattened to its escape-index sequence, and its statistics (buildMs
// covers construction and flattening). The CPU sequence walk and the GPU
// kernel both start from this.
struct SequenceBuild {
  EscapeSequence sequence;
  AccelStats stats;
};
SequenceBuild buildKayKajiyaSequence(std::span<const Triangle> tris, const KayKajiyaConfig& config);

// Node, leaf, reference and depth counts of a BVH with one triangle per leaf,
// and its memory as the thesis counts it (8 floats per box), named `name`.
// buildMs is left 0.
AccelStats bvhStats(const std::string& name, const Bvh& bvh);

// The registry's factories (accel/registry.cpp). Reads: -c (K/K), -t (G/S).
std::unique_ptr<CpuAccelerator> makeKkBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeGsBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKkBvhRecursiveCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeGsBvhRecursiveCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeKkBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
std::unique_ptr<GpuTraversal> makeGsBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
// bvh-octant: bvh-stack's tree (--bvh-builder) as eight octant-ordered sequences (accel/bvh/octant_sequences.h).
std::unique_ptr<CpuAccelerator> makeOctantBvhCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeOctantBvhStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
// bvh-octant-fused: bvh-octant whose primary bounce the renderer runs as one fused pass.
std::unique_ptr<GpuTraversal> makeOctantBvhFusedStream(std::span<const Triangle> tris,
                                                       const GpuTraversalConfig& config);

// The two CPU forms for a tree built elsewhere (tests build trees by hand):
// the sequence walk, and the recursive descent (holds a span of tris).
std::unique_ptr<CpuAccelerator> makeSequenceAccelerator(SequenceBuild build,
                                                        TriangleTest test = TriangleTest::MollerTrumbore);
std::unique_ptr<CpuAccelerator> makeRecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats,
                                                            TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
