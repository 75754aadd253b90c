#pragma once
// The wide BVH's registry entry (CPU only): binned SAH build on all cores
// (--threads), or with --bvh8-builder sbvh the spatial-split build (one
// thread; sbvh_binary_bvh.h), collapsed to 8 wide, traversed with AVX2 where the CPU has it
// (scalar otherwise). Statistics: wide nodes and leaves, the binary tree's SAH
// cost (binary_bvh.h's constants), floatsPerTriangle = node floats per triangle.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeBvh8Cpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
// The same tree traced by the batch entry point: primary and shadow rays as
// packets of 32 (8x4 pixels) sharing one traversal (AVX2 with the
// Möller–Trumbore test; else the per-ray loop), other rays one at a time.
std::unique_ptr<CpuAccelerator> makeBvh8PacketCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
