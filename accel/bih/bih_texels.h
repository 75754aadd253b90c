#pragma once
// A BIH flattened into RGBA float texels for the GPU (kernels_glsl/bih/), plus
// its triangle lists in the shared ReferenceLists format. One texel per node,
// in Bih::nodes order (the left child of an inner node is the next node):
//   inner: (packIndex(rightChild), leftMax, rightMin, -(axis + 2))   w = -2, -3, -4
//   leaf:  (0, 0, 0, list)   list = -1 when empty, else the packed entry index
//          of the leaf's first list entry
// The triangles themselves go in triangleVertexTexels (reference_lists.h).

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bih/bih.h"

namespace passtrace {

struct BihTexels {
  std::vector<glm::vec4> nodes;
  std::vector<glm::vec4> lists;  // ReferenceLists::texels()
  size_t listEntries = 0;        // before padding
  double floatsPerTriangle = 0;  // thesis Table 3: (4 nodes + listEntries) / triangles
};

BihTexels flattenBih(const Bih& bih, size_t triangleCount);

}  // namespace passtrace
