#pragma once
// The octree's registry entry (thesis 9.4; CPU only): traversed front to
// back, built with OctreeConfig's defaults (it reads no flag). Statistics:
// octree nodes, leaves, references and levels; floatsPerTriangle =
// Octree::floatsPerTriangle.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeOctreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
