#pragma once
// Ropes for a kd-tree (Havran 1998; Popov et al. 2007, "Stackless KD-Tree
// Traversal for High Performance GPU Ray Tracing"): each leaf links each of its
// six faces to the smallest node on the other side that still covers the whole
// face, so a ray leaving a leaf goes on from there without a stack. A face on
// the scene boundary has no rope (kNoHit): leaving through it exits the scene.
//
// Flattened for the GPU (flattenKdRopes), nodes have variable size and are
// addressed by texel offset, depth-first so an internal node's left child
// starts at the next texel:
//   internal, 1 texel: (packIndex(right child's offset), split, 0, -(axis + 2))
//   leaf, 4 texels:    (rope -x, rope -y, rope -z, list)   list = -1 if empty
//                      (rope +x, rope +y, rope +z, 0)
//                      (box.min, 0)
//                      (box.max, 0)
// where a rope is packIndex(target offset), or -1 for none, and list is the
// packed entry of the leaf's first reference (accel/reference_lists.h).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "accel/kd/kd_tree.h"

namespace passtrace {

// Face f of a box: axis f / 2, the max side when f is odd (0 = -x, 1 = +x, ...).
inline constexpr int kKdFaces = 6;
using KdLeafRopes = std::array<uint32_t, kKdFaces>;  // node indices, kNoHit = scene boundary

// Ropes of every node, indexed like tree.nodes; internal nodes' entries are
// all kNoHit. Each rope is pushed down to the deepest node covering the face.
std::vector<KdLeafRopes> buildKdRopes(const KdTree& tree);

struct KdRopesTexels {
  std::vector<glm::vec4> nodes;
  std::vector<glm::vec4> lists;   // ReferenceLists::texels()
  std::vector<uint32_t> offsets;  // texel offset of each tree node
  size_t listEntries = 0;
  double floatsPerTriangle = 0;   // (4 node texels + listEntries) / triangles; 0 without triangles
};

inline constexpr uint32_t kKdRopesInternalTexels = 1;
inline constexpr uint32_t kKdRopesLeafTexels = 4;

KdRopesTexels flattenKdRopes(const KdTree& tree, const std::vector<KdLeafRopes>& ropes, size_t triangleCount);

}  // namespace passtrace
