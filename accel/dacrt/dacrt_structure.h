#pragma once
// The registry's "dacrt" row (accel/registry.cpp): divide-and-conquer ray
// tracing on the CPU renderer. It stores nothing, so its build is free and
// the whole work falls in the frame.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeDacrtCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
