#pragma once
// A kd-tree flattened into RGBA float texels for the GPU's restart and
// backtrack traversals (thesis section 8.5, figure 16), plus its triangle
// lists in the shared ReferenceLists format.
//
// Node i occupies texels [i * nodeStride, (i + 1) * nodeStride); node
// indices stored in texels are node indices (the GPU multiplies by
// nodeStride), packed with packIndex. Texel 0 of a node:
//   internal: (packIndex(rightChild), split, parent, -(axis + 2))   w = -2, -3, -4 for x, y, z
//   leaf:     (0, 0, parent, list)   list = -1 for an empty leaf, else the
//             packed entry index of the leaf's first list entry
// where parent = -1 for the root, else packIndex(parent). The left child of
// an internal node is the next node. The backtrack layout adds, for every
// node, texel 1 = (box.min, 0) and texel 2 = (box.max, 0): its voxel.
// The triangles themselves go in triangleVertexTexels (reference_lists.h).

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "accel/kd/kd_tree.h"

namespace passtrace {

struct KdTexels {
  std::vector<glm::vec4> nodes;
  std::vector<glm::vec4> lists;  // ReferenceLists::texels()
  uint32_t nodeStride = 1;       // texels per node: 1 restart, 3 backtrack
  size_t listEntries = 0;        // ReferenceLists::entries().size(), before padding
  double floatsPerTriangle = 0;  // thesis Table 3: (4 nodeStride nodes + listEntries) / triangles
};

inline constexpr uint32_t kKdRestartStride = 1;
inline constexpr uint32_t kKdBacktrackStride = 3;

// An empty tree gives no texels and 0 floats per triangle.
KdTexels flattenKdRestart(const KdTree& tree, size_t triangleCount);
KdTexels flattenKdBacktrack(const KdTree& tree, size_t triangleCount);
// kd-compact: 8 bytes per node, two nodes per texel (kd_compact_node.h);
// nodeStride 0 marks the layout, floatsPerTriangle counts 2 floats per node.
// Throws std::length_error past kKdCompactMaxPayload nodes or list entries.
KdTexels flattenKdCompact(const KdTree& tree, size_t triangleCount);

// The floatsPerTriangle either flattening reports, without building texels:
// each non-empty leaf's list holds its references and an end marker.
double kdFloatsPerTriangle(const KdTree& tree, size_t triangleCount, uint32_t nodeStride);

}  // namespace passtrace
