// Revelles' child order (accel/octree/octree_revelles.h) against a brute-force
// box test: on random rays, the children it visits are exactly the octants
// whose boxes the ray's line passes through, in the order it enters them.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "accel/octree/octree_revelles.h"

namespace passtrace {
namespace {

Aabb octantBox(const Aabb& box, int octant) {
  const glm::vec3 c = box.center();
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    const bool upper = (octant >> k) & 1;
    b.min[k] = upper ? c[k] : box.min[k];
    b.max[k] = upper ? box.max[k] : c[k];
  }
  return b;
}

// The octants the line passes through with an interval of positive length
// (a ray grazing an edge or corner is a tie either way), by entry t.
std::vector<int> bruteForceOrder(const Aabb& box, const Ray& ray, bool& tie) {
  const glm::vec3 inv = safeInverse(ray.direction);
  std::vector<std::pair<float, int>> entered;
  tie = false;
  for (int o = 0; o < 8; ++o) {
    float tNear, tFar;
    clipToBox(ray.origin, inv, octantBox(box, o), tNear, tFar);
    const float length = tFar - tNear;
    if (std::fabs(length) < 1e-4f) tie = true;
    if (length > 0.0f) entered.emplace_back(tNear, o);
  }
  std::sort(entered.begin(), entered.end());
  for (size_t i = 1; i < entered.size(); ++i) tie = tie || entered[i].first - entered[i - 1].first < 1e-4f;
  std::vector<int> order;
  for (const auto& e : entered) order.push_back(e.second);
  return order;
}

TEST(OctreeRevelles, ChildOrderMatchesBruteForceBoxTests) {
  std::mt19937_64 rng(2000);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const Aabb box{glm::vec3(-1.0f, 0.5f, 2.0f), glm::vec3(1.0f, 2.5f, 4.0f)};
  int compared = 0, multi = 0;
  for (int i = 0; i < 5000; ++i) {
    Ray ray;
    // Origins outside and inside the box, every direction octant.
    ray.origin = box.center() + glm::vec3(u(rng), u(rng), u(rng)) * (i % 2 ? 0.9f : 4.0f);
    ray.direction = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    if (i % 10 == 0) ray.direction[i / 10 % 3] = 0.0f;  // parallel to one family of planes
    bool tie = false;
    const std::vector<int> expected = bruteForceOrder(box, ray, tie);
    if (tie) continue;
    ++compared;
    multi += expected.size() > 1;
    EXPECT_EQ(revellesChildOrder(box, ray), expected) << "ray " << i;
  }
  EXPECT_GT(compared, 4000);
  EXPECT_GT(multi, 1000);
}

TEST(OctreeRevelles, NextChildTableLeavesThroughTheExitPlane) {
  // From each child, the exit axis either steps into the upper half or leaves the parent.
  for (int current = 0; current < 8; ++current)
    for (int axis = 0; axis < 3; ++axis) {
      glm::vec3 t1(5.0f);
      t1[axis] = 1.0f;
      const int next = revellesNextChild(current, t1);
      if ((current >> axis) & 1) EXPECT_EQ(next, kRevellesExit);
      else EXPECT_EQ(next, current | (1 << axis));
    }
}

}  // namespace
}  // namespace passtrace
