#pragma once
// CPU accelerators that run the GPU kernels' own algorithms over the GPU's
// own texels (kd_stream_traversal.h, grid_stream_traversal.h): kd-restart,
// kd-backtrack and the stream grid. They exist for debugging the kernels and
// for checking that GPU and CPU count the same steps (thesis: "kd-restart and
// kd-backtrack also run on the CPU").

#include <memory>
#include <optional>
#include <string>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/grid/grid_texels.h"
#include "accel/kd/kd_stream_traversal.h"
#include "accel/kd/kd_texels.h"

namespace passtrace {

// A kd-tree built and flattened for one stream traversal, as the GPU uploads it.
struct KdStreamBuild {
  KdTexels texels;
  Aabb sceneBox;
  AccelStats stats;         // buildMs covers construction and flattening
  uint64_t maxStepsPerRay;  // no ray of a correct traversal takes more steps
};
KdStreamBuild buildKdStream(KdStreamVariant variant, std::span<const Triangle> tris, const AccelBuildConfig& config);

// A uniform grid built and flattened for the stream traversal.
struct GridStreamBuild {
  GridTexels texels;
  Aabb bounds;
  glm::ivec3 resolution{1};
  AccelStats stats;
  uint64_t maxStepsPerRay;
};
GridStreamBuild buildGridStream(std::span<const Triangle> tris, const AccelBuildConfig& config);

enum class StreamMirror { KdRestart, KdBacktrack, Grid };

// "kd-restart", "kd-backtrack" or "grid-stream"; nullopt for other names.
std::optional<StreamMirror> streamMirrorByName(const std::string& name);

std::unique_ptr<CpuAccelerator> makeStreamMirrorAccelerator(StreamMirror which, std::span<const Triangle> tris,
                                                            const AccelBuildConfig& config);

}  // namespace passtrace
