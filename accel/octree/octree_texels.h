#pragma once
// An octree flattened into RGBA float texels for Revelles' traversal
// (kernels_glsl/octree/), plus its triangle lists in the shared
// ReferenceLists format. Three texels per node, in Octree::nodes order:
//   texel 3i:     (tag, 0, 0, 0)  tag = packed entry of the leaf's first list
//                 entry, -1 for an empty leaf, -2 for an internal node
//   texels 3i+1, 3i+2: the child in octant 0-3 and 4-7 (packed node index,
//                 -1 where the octant is empty); octant bit k = upper half along axis k
// The node boxes are not stored: the traversal derives them from the root's.

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "accel/octree/octree.h"

namespace passtrace {

inline constexpr uint32_t kOctreeNodeStride = 3;

struct OctreeTexels {
  std::vector<glm::vec4> nodes;
  std::vector<glm::vec4> lists;  // ReferenceLists::texels()
  size_t listEntries = 0;        // before padding
  double floatsPerTriangle = 0;  // thesis Table 3: (12 nodes + listEntries) / triangles
};

OctreeTexels flattenOctree(const Octree& octree, size_t triangleCount);

}  // namespace passtrace
