#include "tests/bvh_checks.h"

#include <cmath>
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


bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

bool containsPoint(const Aabb& box, const glm::vec3& p) {
  const glm::vec3 slack = 1e-6f * (glm::abs(box.min) + glm::abs(box.max) + glm::abs(p));
  return glm::all(glm::lessThanEqual(box.min - slack, p)) && glm::all(glm::lessThanEqual(p, box.max + slack));
}

bool finiteTriangle(const Triangle& t) {
  for (const glm::vec3& v : {t.v0, t.v1, t.v2})
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return false;
  return true;
}

void expectTriangleInBoxes(const Triangle& tri, std::span<const Aabb> boxes, size_t index) {
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; i + j <= 8; ++j) {
      const float u = float(i) / 8.0f, v = float(j) / 8.0f;
      const glm::vec3 p = tri.v0 + u * (tri.v1 - tri.v0) + v * (tri.v2 - tri.v0);
      bool inside = false;
      for (const Aabb& b : boxes) inside = inside || containsPoint(b, p);
      EXPECT_TRUE(inside) << "triangle " << index << " point (" << u << ", " << v << ")";
    }
}

}  // namespace passtrace::test
