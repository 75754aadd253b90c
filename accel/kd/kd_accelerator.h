#pragma once
// CPU accelerators 2 ("kd-tree": the SAH builder with split clipping, tracy
// -e and -d from AccelBuildConfig) and 3 ("kd-pbrt": built the pbrt way with
// pbrt's constants; a nonzero kdMaxDepth overrides pbrt's depth,
// kdMinElements is not used since pbrt's maxPrims is 1). Both are traversed
// by traverseKdTree. Their stats report the restart layout's floats per
// triangle (kd_texels.h).

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

// The SAH builder's config for accelerator 2 (kdMinElements, kdMaxDepth).
KdBuildConfig kdConfigFor(const AccelBuildConfig& config);
// pbrt's config for accelerator 3, with kdMaxDepth when nonzero.
KdBuildConfig kdPbrtConfigFor(const AccelBuildConfig& config);

// number is 2 or 3; throws std::invalid_argument otherwise. Holds a span of
// tris: the caller keeps them alive and unchanged.
std::unique_ptr<CpuAccelerator> makeKdCpuAccelerator(int number, std::span<const Triangle> tris,
                                                     const AccelBuildConfig& config);

}  // namespace passtrace
