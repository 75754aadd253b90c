#pragma once
// The BIH family's registry entries: "bih" on the GPU (gpu_bih_traversal.h)
// and on the CPU, where it runs the kernel's algorithm over the same texels
// (bih_stream_traversal.h), so the CPU row is also the kernel's mirror. Its
// build parameters are BihConfig's defaults; no flag reads them.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeBihCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeBihStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
