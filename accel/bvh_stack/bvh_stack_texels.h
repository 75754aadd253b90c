#pragma once
// A BinaryBvh as the stream traversal reads it (kernels_glsl/bvh_stack/):
// node i is 4 texels from 4i, a child slot per pair:
//   (child.box.min, link) (child.box.max, count)      slot 0, then slot 1
// link = packIndex(node index) for an internal child (count 0), packIndex(first
// reference entry) for a leaf (count > 0 references), -1 for an absent slot.
// References are packed triangle indices, four per texel (fetchScalar); the
// triangles are triangleVertexTexels (reference_lists.h).

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh_stack/binary_bvh.h"

namespace passtrace {

inline constexpr uint32_t kBvhStackNodeTexels = 4;
inline constexpr float kBvhStackAbsent = -1.0f;

struct BvhStackTexels {
  std::vector<glm::vec4> nodes;
  std::vector<glm::vec4> references;
  double floatsPerTriangle = 0;  // (16 per node + 1 per reference) / triangles
};

BvhStackTexels flattenBvhStack(const BinaryBvh& bvh, size_t triangleCount);

}  // namespace passtrace
