#pragma once
// The escape-index sequence (thesis 9.4, "partial evaluation" of the
// recursive descent): the tree flattened depth first into RGBA texels, each
// box carrying the index where traversal resumes when the ray misses it.
// The GLSL kernel reads exactly this layout:
//
//   box (internal node), 2 texels:
//     [i]   (min.x, min.y, min.z, packIndex(escape))
//     [i+1] (max.x, max.y, max.z, 0)
//   triangle (leaf), 3 texels:
//     [i]   (v0.x, v0.y, v0.z, -1)   negative w marks a triangle
//     [i+1] (v1.x, v1.y, v1.z, packIndex(scene triangle index))
//     [i+2] (v2.x, v2.y, v2.z, 0)
//
// escape is the texel index just after the box's subtree, texels.size() for
// boxes on the right edge of the tree; a triangle's escape is implicitly i+3.
// Packed indices are positive floats (stream/texel_address.h), so w >= 0
// tells a box from a triangle with the first read.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"
#include "stream/texel_address.h"

namespace passtrace {

struct EscapeSequence {
  std::vector<glm::vec4> texels;
  uint32_t boxCount = 0;       // internal nodes
  uint32_t triangleCount = 0;  // leaves

  // Memory overhead as the thesis counts it (Table 3): 8 floats per box,
  // triangles excluded as every structure stores them. A binary tree with one
  // triangle per leaf has N - 1 boxes, giving 8 (N - 1) / N.
  float floatsPerTriangle() const {
    return triangleCount == 0 ? 0.0f : 8.0f * static_cast<float>(boxCount) / static_cast<float>(triangleCount);
  }
};

// Depth first, children in stored order. Throws std::invalid_argument for a
// leaf whose triangle index is outside tris, std::length_error when the
// sequence would exceed the packable index range.
EscapeSequence flattenEscapeSequence(const Bvh& bvh, std::span<const Triangle> tris);

}  // namespace passtrace
