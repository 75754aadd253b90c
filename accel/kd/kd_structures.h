#pragma once
// The kd-tree family's registry entries. One SAH builder with split clipping
// (tracy's -e, -d) serves "kd-tree" (CPU stack traversal) and the two GPU
// stream traversals "kd-restart" and "kd-backtrack" (thesis 8.5), whose CPU
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
// pbrt's config, with kdMaxDepth when nonzero.
KdBuildConfig kdPbrtConfigFor(const AccelBuildConfig& config);

// A kd-tree built and flattened for one stream traversal, as the GPU uploads it.
struct KdStreamBuild {
  KdTexels texels;
  Aabb sceneBox;
  AccelStats stats;         // buildMs covers construction and flattening
  uint64_t maxStepsPerRay;  // no ray of a correct traversal takes more steps
};
KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config);
// The flattening half of buildKdStream, for a tree built elsewhere (dynamic
// scenes: a merged tree, the two trees); stats.buildMs is left 0.
KdStreamBuild flattenKdStream(KdStreamVariant variant, const KdTree& tree, size_t triangleCount);

// The registry's factories (accel/registry.cpp).
std::unique_ptr<CpuAccelerator> makeKdTreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdPbrtCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdRestartMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<CpuAccelerator> makeKdBacktrackMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeKdRestartStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
std::unique_ptr<GpuTraversal> makeKdBacktrackStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
