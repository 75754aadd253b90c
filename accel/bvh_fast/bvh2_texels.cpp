#include "accel/bvh_fast/bvh2_texels.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <utility>

namespace passtrace {

// texel_address.glsl: the index's bits offset into the normal floats.
float packBvh2Index(uint32_t index) { return std::bit_cast<float>(index + 0x00800000u); }
uint32_t unpackBvh2Index(float packed) { return std::bit_cast<uint32_t>(packed) - 0x00800000u; }

Bvh2Texels packBvh2(const Bvh& bvh, std::span<const Triangle> tris) {
  Bvh2Texels out;
  out.triangles.reserve(3 * tris.size());
  for (const Triangle& t : tris)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) out.triangles.emplace_back(v, 0.0f);
  if (bvh.empty()) return out;

  // Internal nodes in depth-first order (near child = the builder's first);
  // a lone leaf root becomes a node with one triangle child.
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 1u}};  // (tree node, its level)
  std::vector<uint32_t> slotOf(bvh.nodes.size(), 0);
  std::vector<uint32_t> order;
  while (!stack.empty()) {
    const auto [index, level] = stack.back();
    stack.pop_back();
    out.depth = std::max(out.depth, level);
    slotOf[index] = uint32_t(order.size());
    order.push_back(index);
    const BvhNode& node = bvh.nodes[index];
    if (node.childCount > 2) throw std::invalid_argument("packBvh2: a node with more than two children");
    for (uint32_t c = node.childCount; c-- > 0;) {
      const uint32_t child = bvh.children[node.firstChild + c];
      if (!bvh.nodes[child].isLeaf()) stack.emplace_back(child, level + 1);
    }
  }
  out.nodes.resize(4 * order.size(), glm::vec4(0.0f));
  for (size_t slot = 0; slot < order.size(); ++slot) {
    const BvhNode& node = bvh.nodes[order[slot]];
    const auto put = [&](uint32_t c, const BvhNode& child, uint32_t childIndex) {
      glm::vec4* t = &out.nodes[4 * slot + 2 * c];
      t[0] = glm::vec4(child.box.min, 0.0f);
      t[1] = glm::vec4(child.box.max, 0.0f);
      if (child.isLeaf()) {
        t[0].w = packBvh2Index(child.triangle);
        t[1].w = kBvh2Triangle;
      } else {
        t[0].w = packBvh2Index(slotOf[childIndex]);
        t[1].w = kBvh2Node;
      }
    };
    if (node.isLeaf()) {
      put(0, node, 0);
      continue;
    }
    for (uint32_t c = 0; c < node.childCount; ++c) {
      const uint32_t child = bvh.children[node.firstChild + c];
      put(c, bvh.nodes[child], child);
    }
  }
  return out;
}

}  // namespace passtrace
