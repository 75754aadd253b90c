#include "accel/bvh/escape_sequence.h"

#include <stdexcept>
#include <string>

namespace passtrace {
namespace {

constexpr uint64_t kBoxTexels = 2;
constexpr uint64_t kTriangleTexels = 3;
constexpr uint64_t kMaxPackable = 0x7F000000u;  // packIndex is valid below this

}  // namespace

EscapeSequence flattenEscapeSequence(const Bvh& bvh, std::span<const Triangle> tris) {
  EscapeSequence seq;
  if (bvh.nodes.empty()) return seq;

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
    uint64_t size = node.isLeaf() ? kTriangleTexels : kBoxTexels;
    for (uint32_t c = 0; c < node.childCount; ++c) size += subtree[bvh.children[node.firstChild + c]];
    subtree[*it] = size;
  }
  if (subtree[0] >= kMaxPackable)
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
      const Triangle& tri = tris[node.triangle];
      out[at] = glm::vec4(tri.v0, -1.0f);
      out[at + 1] = glm::vec4(tri.v1, packIndex(node.triangle));
      out[at + 2] = glm::vec4(tri.v2, 0.0f);
      at += kTriangleTexels;
      ++seq.triangleCount;
    } else {
      const auto escape = static_cast<uint32_t>(at + subtree[index]);
      out[at] = glm::vec4(node.box.min, packIndex(escape));
      out[at + 1] = glm::vec4(node.box.max, 0.0f);
      at += kBoxTexels;
      ++seq.boxCount;
    }
  }
  return seq;
}

}  // namespace passtrace
