#include "accel/bvh/octant_sequences.h"

#include <algorithm>

namespace passtrace {

Bvh orderChildrenForOctant(const Bvh& bvh, uint32_t octant) {
  const glm::vec3 diagonal((octant & 1u) ? -1.0f : 1.0f, (octant & 2u) ? -1.0f : 1.0f, (octant & 4u) ? -1.0f : 1.0f);
  Bvh ordered = bvh;
  for (const BvhNode& node : ordered.nodes) {
    auto first = ordered.children.begin() + node.firstChild;
    // Box centres along the diagonal: a ray of this octant reaches smaller values first.
    std::stable_sort(first, first + node.childCount, [&](uint32_t a, uint32_t b) {
      const Aabb& boxA = ordered.nodes[a].box;
      const Aabb& boxB = ordered.nodes[b].box;
      return glm::dot(boxA.min + boxA.max, diagonal) < glm::dot(boxB.min + boxB.max, diagonal);
    });
  }
  return ordered;
}

OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris) {
  OctantSequences out;
  for (uint32_t octant = 0; octant < kOctants; ++octant)
    out.sequences[octant] = flattenEscapeSequence(orderChildrenForOctant(bvh, octant), tris);
  return out;
}

}  // namespace passtrace
