#pragma once
// The stack BVH traversal (Aila & Laine 2009) on the CPU, step for step as
// kernels_glsl/bvh_stack/bvh_stack_traversal.glsl runs it on the GPU over the
// same texels (bvh_stack_texels.h), so both count the same steps and
// triangle tests (tests/gl/gpu_traversal_test.cpp compares them). A step
// visits a node (both child boxes tested; the nearer hit child entered, the
// farther pushed) or tests one reference of the current leaf. A child whose
// box the ray enters at or beyond the current hit is skipped, also when it
// is popped; shadow rays stop at their first hit.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct BvhStackData {
  std::span<const glm::vec4> nodes, references, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;  // as the kernel is compiled
  uint32_t stackSize = 1;  // entries; the tree's depth suffices
};

// A child waiting on the stack: as the kernel's record keeps it.
struct BvhStackEntry {
  uint32_t link = 0, count = 0;  // as in the node texels
  float tNear = 0;               // where the ray enters its box
};

// A ray's state between passes: where it is (a node, or the next reference
// of a leaf with `count` left), its hit, counters and stack.
struct BvhStackCursor {
  uint32_t link = 0, count = 0;
  Hit best;
  RayStats stats;
  bool done = false;
  std::vector<BvhStackEntry> stack;
};

// bvh_stack_init.frag: at the root, empty stack; done for an empty tree.
BvhStackCursor bvhStackStart(const BvhStackData& data, const Ray& ray);
// Up to maxSteps steps of bvh_stack_traverse.frag; true while work remains.
bool bvhStackSteps(const BvhStackData& data, const Ray& ray, bool anyHit, BvhStackCursor& cursor, uint32_t maxSteps);
// Start and steps to the end.
Hit traverseBvhStack(const BvhStackData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
