#include "tests/bvh_checks.h"

#include <vector>

#include <gtest/gtest.h>

namespace passtrace::test {

void expectValidBvh(const Bvh& bvh, std::span<const Triangle> tris) {
  if (tris.empty()) {
    EXPECT_TRUE(bvh.nodes.empty());
    return;
  }
  ASSERT_FALSE(bvh.nodes.empty());
  std::vector<int> nodeSeen(bvh.nodes.size(), 0), triSeen(tris.size(), 0);
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const uint32_t index = stack.back();
    stack.pop_back();
    ASSERT_LT(index, bvh.nodes.size());
    ASSERT_EQ(nodeSeen[index]++, 0) << "node " << index << " reached twice";
    const BvhNode& node = bvh.nodes[index];
    if (node.isLeaf()) {
      ASSERT_LT(node.triangle, tris.size());
      ++triSeen[node.triangle];
      const Aabb b = tris[node.triangle].bounds();
      EXPECT_EQ(node.box.min, b.min);
      EXPECT_EQ(node.box.max, b.max);
      continue;
    }
    EXPECT_EQ(node.triangle, kNoHit);
    EXPECT_GE(node.childCount, 2u) << "an internal node with one child is wasted";
    ASSERT_LE(size_t{node.firstChild} + node.childCount, bvh.children.size());
    for (uint32_t c = 0; c < node.childCount; ++c) {
      const uint32_t child = bvh.children[node.firstChild + c];
      ASSERT_LT(child, bvh.nodes.size());
      const Aabb& cb = bvh.nodes[child].box;
      EXPECT_TRUE(glm::all(glm::lessThanEqual(node.box.min, cb.min)) &&
                  glm::all(glm::greaterThanEqual(node.box.max, cb.max)))
          << "node " << index << " does not enclose child " << child;
      stack.push_back(child);
    }
  }
  for (size_t n = 0; n < nodeSeen.size(); ++n) EXPECT_EQ(nodeSeen[n], 1) << "node " << n;
  for (size_t t = 0; t < triSeen.size(); ++t) EXPECT_EQ(triSeen[t], 1) << "triangle " << t;
}


}  // namespace passtrace::test
