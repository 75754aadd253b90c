#pragma once
// The bvh-fast row's factories (accel/registry.cpp): Kay/Kajiya's binary BVH
// packed two children per node (bvh2_texels.h), on the GPU stream renderer
// and, as the kernel's algorithm, on the CPU.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeBvhFastMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeBvhFastStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
