#pragma once
// A binary BVH packed for one fragment kernel that walks it near child first
// with a per-ray stack (kernels_glsl/bvh_fast/): each node holds both
// children's boxes, so one step tests two boxes with four texel fetches, and a
// child that is a single triangle is tested in place of its box.
//
// Node n is texels 4n .. 4n+3:
//   (child 0 box min, child 0 ref), (child 0 box max, child 0 kind),
//   (child 1 box min, child 1 ref), (child 1 box max, child 1 kind)
// kind: 0 no child, 1 a node (ref = packed node index), 2 a triangle
// (ref = packed triangle id; its 3 vertices are triangle texels 3 id .. 3 id + 2).

#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"

namespace passtrace {

inline constexpr float kBvh2NoChild = 0.0f, kBvh2Node = 1.0f, kBvh2Triangle = 2.0f;

struct Bvh2Texels {
  std::vector<glm::vec4> nodes;      // 4 per node; empty for an empty scene
  std::vector<glm::vec4> triangles;  // 3 per scene triangle, scene order
  uint32_t depth = 0;                // nodes on the longest root-to-leaf path: the stack never holds more
};

// Packs a binary BVH (Kay/Kajiya's) whose leaves hold one triangle each.
Bvh2Texels packBvh2(const Bvh& bvh, std::span<const Triangle> tris);

// The float a kernel stores an index as (texel_address.glsl's packIndex).
float packBvh2Index(uint32_t index);
uint32_t unpackBvh2Index(float packed);

}  // namespace passtrace
