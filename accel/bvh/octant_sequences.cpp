#include "accel/bvh/octant_sequences.h"

#include <algorithm>
#include <stdexcept>
#include <string>

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

namespace {

glm::vec3 octantDiagonal(uint32_t octant) {
  return {(octant & 1u) ? -1.0f : 1.0f, (octant & 2u) ? -1.0f : 1.0f, (octant & 4u) ? -1.0f : 1.0f};
}

// `node`'s children (indices into bvh.nodes) in the octant's order: box centres
// along the diagonal, where a ray of this octant reaches smaller values first;
// ties keep stored order.
void sortChildrenForOctant(const Bvh& bvh, glm::vec3 diagonal, uint32_t* first, uint32_t count) {
  std::stable_sort(first, first + count, [&](uint32_t a, uint32_t b) {
    const Aabb& boxA = bvh.nodes[a].box;
    const Aabb& boxB = bvh.nodes[b].box;
    return glm::dot(boxA.min + boxA.max, diagonal) < glm::dot(boxB.min + boxB.max, diagonal);
  });
}

// Texels of every subtree with LeafTexels::Shared; ordering children moves
// subtrees without resizing them, so one count serves the eight octants.
std::vector<uint32_t> sharedSubtreeTexels(const Bvh& bvh) {
  std::vector<uint32_t> preorder;
  preorder.reserve(bvh.nodes.size());
  for (std::vector<uint32_t> stack{0}; !stack.empty();) {
    const uint32_t index = stack.back();
    stack.pop_back();
    preorder.push_back(index);
    const BvhNode& node = bvh.nodes[index];
    stack.insert(stack.end(), bvh.children.begin() + node.firstChild,
                 bvh.children.begin() + node.firstChild + node.childCount);
  }
  std::vector<uint32_t> subtree(bvh.nodes.size(), 0);
  for (auto it = preorder.rbegin(); it != preorder.rend(); ++it) {
    const BvhNode& node = bvh.nodes[*it];
    uint64_t size = node.isLeaf() ? leafTexelCount(LeafTexels::Shared) : kOctantBoxTexels;
    for (uint32_t c = 0; c < node.childCount; ++c) size += subtree[bvh.children[node.firstChild + c]];
    if (size >= kMaxSequenceTexels)
      throw std::length_error("bvh-octant: a sequence of " + std::to_string(size) +
                              " texels exceeds the packable index range");
    subtree[*it] = uint32_t(size);
  }
  return subtree;
}

}  // namespace

Bvh orderChildrenForOctant(const Bvh& bvh, uint32_t octant) {
  Bvh ordered = bvh;
  for (const BvhNode& node : ordered.nodes)
    sortChildrenForOctant(ordered, octantDiagonal(octant), ordered.children.data() + node.firstChild, node.childCount);
  return ordered;
}

BoxGrid octantBoxGrid(const Bvh& bvh) { return bvh.empty() ? BoxGrid{} : BoxGrid::over(bvh.nodes[0].box); }

OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris) {
  OctantSequences out;
  const BoxGrid grid = octantBoxGrid(bvh);
  for (uint32_t octant = 0; octant < kOctants; ++octant)
    out.sequences[octant] = flattenEscapeSequence(orderChildrenForOctant(bvh, octant), tris, LeafTexels::Inline, {},
                                                  &grid);
  return out;
}

uint64_t octantSequenceTexels(const Bvh& bvh) {
  // Every box and leaf once: no need to walk the tree.
  const uint64_t leaves = bvh.leafCount();
  return bvh.empty() ? 0 : leaves * leafTexelCount(LeafTexels::Shared) + (bvh.nodes.size() - leaves) * kOctantBoxTexels;
}

void writeOctantSequences(const Bvh& bvh, std::span<const Triangle> tris,
                          const std::function<void(uint64_t first, std::span<const glm::vec4> texels)>& write) {
  if (bvh.empty()) return;
  const std::vector<uint32_t> subtree = sharedSubtreeTexels(bvh);
  const std::vector<uint32_t> slots = leafSlots(bvh);
  const uint64_t size = subtree[0];
  const BoxGrid grid = octantBoxGrid(bvh);
  std::vector<glm::vec4> chunk(kOctantWriteTexels + kOctantBoxTexels);
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    const glm::vec3 diagonal = octantDiagonal(octant);
    uint64_t chunkFirst = 0;  // the chunk's first texel within the sequence
    size_t filled = 0;
    uint32_t at = 0;          // the texel being written, within the sequence
    std::vector<uint32_t> stack{0};  // explicit pre-order work stack
    while (!stack.empty()) {
      const uint32_t index = stack.back();
      stack.pop_back();
      const BvhNode& node = bvh.nodes[index];
      if (node.isLeaf()) {
        if (node.triangle >= tris.size())
          throw std::invalid_argument("bvh-octant: leaf " + std::to_string(index) + " names triangle " +
                                      std::to_string(node.triangle) + " of " + std::to_string(tris.size()));
        writeLeafTexels(chunk.data() + filled, tris[node.triangle], node.triangle, slots[index], LeafTexels::Shared);
        filled += leafTexelCount(LeafTexels::Shared);
      } else {
        writeBoxTexels(chunk.data() + filled, node.box, at + subtree[index], &grid);
        filled += kOctantBoxTexels;
        const size_t before = stack.size();
        stack.insert(stack.end(), bvh.children.begin() + node.firstChild,
                     bvh.children.begin() + node.firstChild + node.childCount);
        sortChildrenForOctant(bvh, diagonal, stack.data() + before, node.childCount);
        std::reverse(stack.begin() + std::ptrdiff_t(before), stack.end());  // the nearest pops first
      }
      at = uint32_t(chunkFirst + filled);
      if (filled >= kOctantWriteTexels || stack.empty()) {
        write(octant * size + chunkFirst, std::span<const glm::vec4>(chunk.data(), filled));
        chunkFirst += filled;
        filled = 0;
      }
    }
  }
}

}  // namespace passtrace
