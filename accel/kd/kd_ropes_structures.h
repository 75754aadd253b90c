#pragma once
// The "kd-ropes" registry row (seed 002): kd-restart's tree (buildKdTreeFor:
// -e, -d, --kd-builder, --kd-termination) with six ropes per leaf and the
// leaves' boxes (kd_ropes.h), walked stacklessly from the entry point; on the
// CPU the kernel's own algorithm (kd_ropes_traversal.h). Its floats per
// triangle and structure bytes include the ropes and boxes.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeKdRopesMirror(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeKdRopesStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
