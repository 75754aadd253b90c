#include "accel/bvh/escape_sequence.h"

#include <stdexcept>
#include <string>

namespace passtrace {
void writeLeafTexels(glm::vec4* out, const Triangle& tri, uint32_t triangle, uint32_t slot, LeafTexels leaves) {
  if (leaves == LeafTexels::Shared) {
    out[0] = glm::vec4(tri.v0, -packIndex(slot));
    return;
  }
  out[0] = glm::vec4(tri.v0, -1.0f);
  out[1] = glm::vec4(tri.v1, packIndex(triangle));
  out[2] = glm::vec4(tri.v2, 0.0f);
}

std::vector<uint32_t> leafSlots(const Bvh& bvh) {
  std::vector<uint32_t> slots(bvh.nodes.size(), kNoHit);
  uint32_t next = 0;
  for (std::vector<uint32_t> stack = bvh.empty() ? std::vector<uint32_t>{} : std::vector<uint32_t>{0};
       !stack.empty();) {
    const uint32_t index = stack.back();
    stack.pop_back();
    const BvhNode& node = bvh.nodes[index];
    if (node.isLeaf()) slots[index] = next++;
    for (uint32_t c = node.childCount; c-- > 0;) stack.push_back(bvh.children[node.firstChild + c]);
  }
  return slots;
}

std::vector<glm::vec4> sharedTriangleTexels(const Bvh& bvh, std::span<const Triangle> tris,
                                            std::span<const uint32_t> slots) {
  const std::vector<uint32_t> ownSlots = slots.empty() ? leafSlots(bvh) : std::vector<uint32_t>{};
  if (!ownSlots.empty()) slots = ownSlots;
  std::vector<glm::vec4> texels(2 * bvh.leafCount());
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& node = bvh.nodes[i];
    if (!node.isLeaf()) continue;
    if (node.triangle >= tris.size())
      throw std::invalid_argument("sharedTriangleTexels: leaf " + std::to_string(i) + " names triangle " +
                                  std::to_string(node.triangle) + " of " + std::to_string(tris.size()));
    texels[2 * size_t(slots[i])] = glm::vec4(tris[node.triangle].v1, packIndex(node.triangle));
    texels[2 * size_t(slots[i]) + 1] = glm::vec4(tris[node.triangle].v2, 0.0f);
  }
  return texels;
}

EscapeSequence flattenEscapeSequence(const Bvh& bvh, std::span<const Triangle> tris, LeafTexels leaves,
                                     std::span<const uint32_t> slots, const BoxGrid* grid) {
  const uint64_t triangleTexels = leafTexelCount(leaves);
  const std::vector<uint32_t> ownSlots =
      leaves == LeafTexels::Shared && slots.empty() ? leafSlots(bvh) : std::vector<uint32_t>{};
  if (!ownSlots.empty()) slots = ownSlots;
  EscapeSequence seq;
  if (grid) seq.grid = *grid;
  if (bvh.nodes.empty()) return seq;
  const uint64_t boxTexels = boxTexelCount(grid);

  // Pre-order node list (explicit stack, children pushed in reverse so they
  // pop in stored order); it is also the texel order.
  std::vector<uint32_t> preorder;
  preorder.reserve(bvh.nodes.size());
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const uint32_t index = stack.back();
    stack.pop_back();
    preorder.push_back(index);
    const BvhNode& node = bvh.nodes[index];
    for (uint32_t c = node.childCount; c-- > 0;) stack.push_back(bvh.children[node.firstChild + c]);
  }

  // Subtree sizes in texels, children before parents: reverse pre-order.
  std::vector<uint64_t> subtree(bvh.nodes.size(), 0);
  for (auto it = preorder.rbegin(); it != preorder.rend(); ++it) {
    const BvhNode& node = bvh.nodes[*it];
    uint64_t size = node.isLeaf() ? triangleTexels : boxTexels;
    for (uint32_t c = 0; c < node.childCount; ++c) size += subtree[bvh.children[node.firstChild + c]];
    subtree[*it] = size;
  }
  if (subtree[0] >= kMaxSequenceTexels)
    throw std::length_error("flattenEscapeSequence: " + std::to_string(subtree[0]) +
                            " texels exceed the packable index range");

  seq.texels.resize(subtree[0]);
  glm::vec4* out = seq.texels.data();
  uint32_t at = 0;  // texel index of the node being written
  for (const uint32_t index : preorder) {
    const BvhNode& node = bvh.nodes[index];
    if (node.isLeaf()) {
      if (node.triangle >= tris.size())
        throw std::invalid_argument("flattenEscapeSequence: leaf " + std::to_string(index) + " names triangle " +
                                    std::to_string(node.triangle) + " of " + std::to_string(tris.size()));
      writeLeafTexels(out + at, tris[node.triangle], node.triangle, slots.empty() ? 0 : slots[index], leaves);
      at += uint32_t(triangleTexels);
      ++seq.triangleCount;
    } else {
      const auto escape = static_cast<uint32_t>(at + subtree[index]);
      writeBoxTexels(out + at, node.box, escape, grid);
      at += uint32_t(boxTexels);
      ++seq.boxCount;
    }
  }
  return seq;
}

}  // namespace passtrace
