#include "accel/bvh/octant_sequences.h"

#include <algorithm>

namespace passtrace {

Bvh bvhFromBinaryBvh(const BinaryBvh& binary, std::span<const Triangle> tris) {
  Bvh bvh;
  if (binary.empty()) return bvh;
  const auto addNode = [&](const Aabb& box) {
    bvh.nodes.push_back(BvhNode{.box = box});
    return static_cast<uint32_t>(bvh.nodes.size() - 1);
  };
  const auto addLeaf = [&](uint32_t triangle) {
    const uint32_t index = addNode(tris[triangle].bounds());
    bvh.nodes[index].triangle = triangle;
    return index;
  };
  // The node's children, grouped in Bvh::children; a leaf slot of several references becomes a node over them.
  const auto setChildren = [&](uint32_t parent, const std::vector<uint32_t>& kids) {
    bvh.nodes[parent].firstChild = static_cast<uint32_t>(bvh.children.size());
    bvh.nodes[parent].childCount = static_cast<uint32_t>(kids.size());
    bvh.children.insert(bvh.children.end(), kids.begin(), kids.end());
  };

  std::vector<std::pair<uint32_t, uint32_t>> work{{0u, addNode(binary.bounds)}};  // (binary node, Bvh node)
  while (!work.empty()) {
    const auto [from, to] = work.back();
    work.pop_back();
    std::vector<uint32_t> kids;
    for (const BvhChild& child : binary.nodes[from].child) {
      if (!child.present) continue;
      if (!child.isLeaf()) {
        const uint32_t node = addNode(child.box);
        kids.push_back(node);
        work.emplace_back(child.index, node);
      } else if (child.count == 1) {
        kids.push_back(addLeaf(binary.references[child.index]));
      } else {
        const uint32_t group = addNode(child.box);
        std::vector<uint32_t> leaves;
        for (uint32_t r = 0; r < child.count; ++r) leaves.push_back(addLeaf(binary.references[child.index + r]));
        setChildren(group, leaves);
        kids.push_back(group);
      }
    }
    setChildren(to, kids);
  }
  return bvh;
}

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

BackToBackSequences flattenOctantSequencesBackToBack(const Bvh& bvh, std::span<const Triangle> tris) {
  BackToBackSequences out;
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    EscapeSequence sequence = flattenEscapeSequence(orderChildrenForOctant(bvh, octant), tris);
    if (octant == 0) {
      out.sequenceSize = sequence.texels.size();
      out.floatsPerTriangle = sequence.floatsPerTriangle();
      out.texels.reserve(kOctants * sequence.texels.size());  // every octant's is the same size
    }
    out.texels.insert(out.texels.end(), sequence.texels.begin(), sequence.texels.end());
  }
  return out;
}

}  // namespace passtrace
