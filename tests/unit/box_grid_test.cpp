// BoxGrid (accel/bvh/box_grid.h): a quantized box always encloses the exact
// one, is the tightest such box on the grid, and decodes the same whichever
// way the planes are computed; at boxes' edges, huge and tiny coordinates,
// far from the origin and flat.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <stdexcept>

#include "accel/bvh/box_grid.h"

namespace passtrace {
namespace {

// Random boxes inside `bounds`, some with a side on the bounds' faces, some
// points, some one plane from the grid's edge.
std::vector<Aabb> boxesInside(const Aabb& bounds, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Aabb> boxes{bounds, Aabb{bounds.min, bounds.min}, Aabb{bounds.max, bounds.max}};
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 a, b;
    for (int k = 0; k < 3; ++k) {
      const float extent = bounds.max[k] - bounds.min[k];
      a[k] = bounds.min[k] + u(rng) * extent;
      b[k] = i % 3 == 0 ? a[k] : bounds.min[k] + u(rng) * extent;
      if (i % 7 == 0) b[k] = bounds.max[k];
      a[k] = std::clamp(a[k], bounds.min[k], bounds.max[k]);
      b[k] = std::clamp(b[k], bounds.min[k], bounds.max[k]);
    }
    boxes.push_back({glm::min(a, b), glm::max(a, b)});
  }
  return boxes;
}

void expectEnclosingAndTight(const Aabb& bounds, uint32_t seed) {
  const BoxGrid grid = BoxGrid::over(bounds);
  for (int k = 0; k < 3; ++k) {
    int exponent = 0;
    EXPECT_EQ(std::frexp(grid.step[k], &exponent), 0.5f) << "step " << grid.step[k] << " is a power of two";
    EXPECT_TRUE(std::isnormal(grid.step[k]));
    EXPECT_EQ(grid.step[k] * grid.invStep[k], 1.0f);
    EXPECT_GE(double(bounds.min[k]) - grid.plane(k, 0), grid.step[k] / 256.0) << "margin below the bounds";
    EXPECT_GE(grid.plane(k, BoxGrid::kMaxPlane) - double(bounds.max[k]), grid.step[k] / 256.0) << "and above";
  }
  for (const Aabb& box : boxesInside(bounds, seed)) {
    const glm::vec3 texel = grid.encode(box);
    const Aabb planes = BoxGrid::gridPlanes(texel);
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(std::isnormal(texel[k]) && texel[k] > 0.0f) << "a positive normal float";
      const auto lo = uint32_t(planes.min[k]), hi = uint32_t(planes.max[k]);
      const double margin = grid.step[k] / 256.0;
      ASSERT_LE(grid.plane(k, lo), double(box.min[k]) - margin) << "axis " << k << " box min " << box.min[k];
      ASSERT_GE(grid.plane(k, hi), double(box.max[k]) + margin) << "axis " << k << " box max " << box.max[k];
      // Tightest: the next plane inwards would come within the margin.
      if (lo < BoxGrid::kMaxPlane) {
        EXPECT_GT(grid.plane(k, lo + 1), double(box.min[k]) - margin);
      }
      if (hi > lo) {
        EXPECT_LT(grid.plane(k, hi - 1), double(box.max[k]) + margin);
      }
    }
  }
}

TEST(BoxGrid, EnclosesEveryBoxTightlyAtEveryScale) {
  expectEnclosingAndTight({glm::vec3(0.0f), glm::vec3(1.0f)}, 1);
  expectEnclosingAndTight({glm::vec3(-3.7f, 2.0f, -100.0f), glm::vec3(12.1f, 2.5f, 1e3f)}, 2);
  expectEnclosingAndTight({glm::vec3(-1e30f), glm::vec3(2e30f)}, 3);               // huge
  expectEnclosingAndTight({glm::vec3(1e-30f), glm::vec3(4e-30f)}, 4);              // tiny
  expectEnclosingAndTight({glm::vec3(1e6f), glm::vec3(1e6f + 0.5f)}, 5);           // far from the origin
  expectEnclosingAndTight({glm::vec3(-1e7f, 0.0f, 3.0f), glm::vec3(-1e7f + 1.0f, 0.0f, 3.0f)}, 6);  // flat
}

TEST(BoxGrid, RefusesBoxesOutsideAndBoundsThatAreNotFinite) {
  const BoxGrid grid = BoxGrid::over({glm::vec3(0.0f), glm::vec3(1.0f)});
  EXPECT_THROW(grid.encode({glm::vec3(-0.5f), glm::vec3(0.5f)}), std::invalid_argument);
  EXPECT_THROW(grid.encode({glm::vec3(0.5f), glm::vec3(1e9f)}), std::invalid_argument);
  EXPECT_THROW(BoxGrid::over({glm::vec3(0.0f), glm::vec3(INFINITY)}), std::invalid_argument);
  EXPECT_THROW(BoxGrid::over({glm::vec3(NAN), glm::vec3(1.0f)}), std::invalid_argument);
  EXPECT_THROW(BoxGrid::over({glm::vec3(-3e38f), glm::vec3(3e38f)}), std::invalid_argument);
}

// t along the grid ray is t along the world ray: a box's entry and exit in
// grid units bracket the world box's (the quantized box encloses it), for rays
// from inside, from afar and along the faces.
TEST(BoxGrid, GridRaysEnterWhereWorldRaysDo) {
  const Aabb bounds{glm::vec3(-3.7f, 1e3f, 0.25f), glm::vec3(12.1f, 1e3f + 3.0f, 0.25f)};
  const BoxGrid grid = BoxGrid::over(bounds);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  size_t entered = 0;
  for (const Aabb& box : boxesInside(bounds, 8)) {
    const glm::vec3 texel = grid.encode(box);
    for (int r = 0; r < 4; ++r) {
      const glm::vec3 target = 0.5f * (box.min + box.max) + 0.3f * (box.max - box.min) * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      if (r == 3) d = glm::vec3(0.0f, 0.0f, 1.0f);  // parallel to two slabs
      const float distance = r == 0 ? 0.0f : r == 1 ? 20.0f : 1e5f;
      const glm::vec3 origin = target - distance * d;
      const glm::vec3 invDir = safeInverse(d);
      const bool world = intersectsBox(origin, invDir, box, kInfinity);
      const bool gridded = BoxGrid::intersects(grid.ray(origin, invDir), texel, kInfinity);
      if (world) {
        ASSERT_TRUE(gridded) << "a ray that enters the box enters its quantized box";
      }
      entered += world;
    }
  }
  EXPECT_GT(entered, 4000u);
}

}  // namespace
}  // namespace passtrace
