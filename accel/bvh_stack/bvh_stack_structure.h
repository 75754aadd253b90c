#pragma once
// The registry row "bvh-stack": a binary BVH in the Aila–Laine layout built
// by --bvh-builder (sah, sbvh or middle), traversed with a stack of node
// links, nearer child first. The CPU renderer runs the kernel's algorithm
// over the GPU's texels (bvh_stack_traversal.h), so both count the same work.

#include <cstdint>
#include <memory>
#include <span>

#include "accel/bvh_stack/binary_bvh.h"
#include "accel/bvh_stack/bvh_builder_kind.h"
#include "accel/bvh_stack/bvh_stack_texels.h"
#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

// The tree of the chosen builder.
BinaryBvh buildBvhStackTree(std::span<const Triangle> tris, BvhBuilderKind builder,
                            const BvhStackConfig& config = {});

// A tree built and flattened as the stream traversal uploads it.
struct BvhStackBuild {
  BvhStackTexels texels;
  AccelStats stats;         // buildMs covers construction and flattening
  uint32_t stackSize = 1;   // the tree's depth
  uint64_t maxStepsPerRay;  // each node visited and each reference tested at most once
};
BvhStackBuild buildBvhStack(std::span<const Triangle> tris, const AccelBuildConfig& config);

// The registry's factories (accel/registry.cpp). Reads --bvh-builder.
std::unique_ptr<CpuAccelerator> makeBvhStackCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<GpuTraversal> makeBvhStackStream(std::span<const Triangle> tris, const GpuTraversalConfig& config);

}  // namespace passtrace
