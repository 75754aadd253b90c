#pragma once
// The octree's registry entries, built with OctreeConfig's defaults (they read
// no flag). Statistics: octree nodes, leaves, references and levels.
//   octree:         Revelles et al. 2000's parametric traversal, on the GPU
//                   (gpu_octree_traversal.h) and on the CPU as the kernel's
//                   algorithm over the same texels (octree_stream_traversal.h);
//                   floatsPerTriangle of its texels (octree_texels.h).
//   octree-descent: the CPU's front-to-back descent with box tests
//                   (traverseOctree); floatsPerTriangle = Octree::floatsPerTriangle.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

std::unique_ptr<CpuAccelerator> makeOctreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeOctreeStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);
std::unique_ptr<CpuAccelerator> makeOctreeDescentCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
