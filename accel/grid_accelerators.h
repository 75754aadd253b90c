#pragma once
// CPU accelerators 1, 4, 6 and 7 of thesis Table 4: the Goldsmith/Salmon BVH
// walked as its escape-index sequence (1) and recursively (6), the uniform
// grid (4) and the octree (7). makeCpuAccelerator dispatches here.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"
#include "accel/geometry/geometry.h"

namespace passtrace {

// number must be 1, 4, 6 or 7 (std::invalid_argument otherwise). As with
// makeCpuAccelerator, the accelerator holds a span of tris: the caller keeps
// them alive and unchanged. Uses config.gsTries and config.gsSeed (1, 6) and
// config.gridMultiplier (4); the octree uses OctreeConfig's defaults.
// Statistics: 1 and 6 count the tree like K/K (8 floats per box); 4 counts
// nodes = cells, leaves = non-empty cells, references = list entries without
// terminators, depth 1, floatsPerTriangle = flattenGrid's; 7 counts octree
// nodes, leaves, references and levels, floatsPerTriangle =
// Octree::floatsPerTriangle. buildMs covers construction (and, for 1, the
// flattening), measured with steady_clock.
std::unique_ptr<CpuAccelerator> makeGridFamilyCpuAccelerator(int number, std::span<const Triangle> tris,
                                                             const AccelBuildConfig& config = {});

}  // namespace passtrace
