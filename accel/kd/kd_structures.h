#pragma once
// The kd-tree family's registry entries. One SAH build with split clipping
// (tracy's -e, -d; --kd-builder exact|binned, --kd-termination thesis|papay:
// buildKdTreeFor) serves "kd-tree" (CPU stack traversal) and the GPU stream
// traversals "kd-restart" and "kd-backtrack" (thesis 8.5) and "kd-pushdown",
// "kd-shortstack", "kd-pushdown-shortstack", "kd-stack" (seed 003 ch. 6;
// --stack-size for the short stacks), whose CPU
// forms are the kernels' own algorithms over the GPU's texels
// (kd_stream_traversal.h). "kd-pbrt" is built the pbrt way with pbrt's
// constants (a nonzero -d overrides pbrt's depth; -e is not read since pbrt's
// maxPrims is 1). The CPU trees report the restart layout's floats per
// triangle (kd_texels.h).

#include <cstdint>
#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"
#include "accel/kd/kd_stream_traversal.h"
#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

// The SAH builder's config (kdMinElements, kdMaxDepth).
KdBuildConfig kdConfigFor(const AccelBuildConfig& config);

// The one kd build of every row but kd-pbrt: the exact or binned SAH builder
// (kdBuilder) with the thesis's or the seed's termination (kdTermination).
KdTree buildKdTreeFor(std::span<const Triangle> tris, const AccelBuildConfig& config);

// Fills the tree's counts and SAH cost (kd_sah_cost.h, the SAH builders'
// constants) into `stats`; structureBytes is the caller's, as it depends on
// the layout traversed.
void setKdTreeStats(AccelStats& stats, const KdTree& tree);

// pbrt's config, with kdMaxDepth when nonzero.
KdBuildConfig kdPbrtConfigFor(const AccelBuildConfig& config);

// A kd-tree built and flattened for one stream traversal, as the GPU uploads it.
struct KdStreamBuild {
  KdTexels texels;
  Aabb sceneBox;
  AccelStats stats;         // buildMs covers construction and flattening
  uint64_t maxStepsPerRay;  // no ray of a correct traversal takes more steps
  uint32_t stackSize = 0;   // stack entries of the stack variants (KdStreamData::stackSize)
};
KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config);
// The flattening half of buildKdStream, for a tree built elsewhere (dynamic
// scenes: a merged tree, the two trees); stats.buildMs is left 0.
KdStreamBuild flattenKdStream(KdStreamVariant variant, const KdTree& tree, size_t triangleCount,
                              int shortStackSize = AccelBuildConfig{}.kdStackSize);

// The registry row name of a stream traversal ("kd-restart", ...): its
// AccelStats::name, and how --dynamic finds a row's variant.
const char* kdStreamName(KdStreamVariant variant);

// The registry's factories (accel/registry.cpp).
std::unique_ptr<CpuAccelerator> makeKdTreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdPbrtCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdRestartMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdBacktrackMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeKdRestartStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
std::unique_ptr<GpuTraversal> makeKdBacktrackStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
// Any stream variant (instantiated for all): the CPU mirror and the GPU kernels.
template <KdStreamVariant V>
std::unique_ptr<CpuAccelerator> makeKdStreamMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
template <KdStreamVariant V>
std::unique_ptr<GpuTraversal> makeKdStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
