// The kd stream traversals of seed 003 ch. 6 on the CPU (their kernels' mirrors,
// accel/kd/kd_stream_traversal.h): the circular stack by hand, and on a deep
// tree the relations that follow from the algorithms. Every restart-family
// traversal visits the same leaves in the same order, so hits and triangle
// tests are the same ray for ray; they differ only in how they reach a leaf:
//   push-down skips the top of restart's re-descents, which would take the
//     same branches again: never more steps than restart;
//   a larger stack drops fewer far children, each drop costing a re-descent:
//     8 entries never take more steps than 1.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/kd/kd_structures.h"
#include "accel/reference_lists.h"
#include "tests/hit_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using Entry = KdCircularStack::Entry;

TEST(KdCircularStack, PopsTheLatestAndAFullStackDropsTheOldest) {
  KdCircularStack stack(2);
  EXPECT_TRUE(stack.empty());
  stack.push({1, 0.0f, 1.0f});
  stack.push({2, 1.0f, 2.0f});
  stack.push({3, 2.0f, 3.0f});  // full: entry 1 is dropped
  EXPECT_EQ(stack.count, 2u);
  EXPECT_EQ(stack.pop().node, 3u);
  const Entry second = stack.pop();
  EXPECT_EQ(second.node, 2u);
  EXPECT_EQ(second.tMin, 1.0f);
  EXPECT_EQ(second.tMax, 2.0f);
  EXPECT_TRUE(stack.empty());

  KdCircularStack one(1);
  for (uint32_t n = 10; n < 15; ++n) one.push({n, 0.0f, 0.0f});
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.pop().node, 14u);
  EXPECT_TRUE(one.empty());

  // Interleaved pushes and pops wrap around the slots.
  KdCircularStack three(3);
  three.push({1, 0, 0});
  three.push({2, 0, 0});
  EXPECT_EQ(three.pop().node, 2u);
  for (uint32_t n = 3; n <= 6; ++n) three.push({n, 0, 0});  // 1 3 4 5 6: 1 and 3 dropped
  EXPECT_EQ(three.pop().node, 6u);
  EXPECT_EQ(three.pop().node, 5u);
  EXPECT_EQ(three.pop().node, 4u);
  EXPECT_TRUE(three.empty());
}

struct Traced {
  std::vector<Hit> hits;
  std::vector<RayStats> stats;
  uint64_t steps = 0;
};

class KdStreamVariants : public ::testing::Test {
 protected:
  void SetUp() override {
    const Aabb box{glm::vec3(0.0f), glm::vec3(10.0f)};
    tris_ = testmesh::triangleSoup(20000, box, 0.4f, 3);
    triangleTexels_ = triangleVertexTexels(tris_);
    rays_ = testmesh::rayMix(testmesh::boundsOf(tris_), 300, 11);
  }

  Traced trace(KdStreamVariant variant, int stackSize = 4) {
    AccelBuildConfig config;
    config.kdStackSize = stackSize;
    const KdStreamBuild build = buildKdStream(variant, tris_, config);
    depth_ = build.stats.depth;
    const KdStreamData data{variant, build.sceneBox, build.texels.nodes, build.texels.lists, triangleTexels_,
                            TriangleTest::MollerTrumbore, build.stackSize};
    Traced out;
    for (size_t i = 0; i < rays_.size(); ++i) {
      RayStats stats;
      out.hits.push_back(traverseKdStream(data, rays_[i], i % 2 == 1, &stats));
      EXPECT_LE(stats.steps, build.maxStepsPerRay) << "ray " << i;
      out.stats.push_back(stats);
      out.steps += stats.steps;
    }
    return out;
  }

  std::vector<Triangle> tris_;
  std::vector<glm::vec4> triangleTexels_;
  std::vector<Ray> rays_;
  uint32_t depth_ = 0;
};

TEST_F(KdStreamVariants, VisitTheSameLeavesAsRestartAndFindBruteForcesHits) {
  const Traced restart = trace(KdStreamVariant::Restart);
  ASSERT_GT(depth_, 12u);  // deep enough for 8 entries to overflow
  size_t found = 0;
  for (size_t i = 0; i < rays_.size(); ++i) {
    const Hit brute = intersectBruteForce(tris_, rays_[i], i % 2 == 1);
    ASSERT_EQ(restart.hits[i].found(), brute.found()) << "ray " << i;
    if (i % 2 == 0 && brute.found()) {
      EXPECT_TRUE(restart.hits[i].id == brute.id || test::tiedT(restart.hits[i].t, brute.t)) << "ray " << i;
    }
    found += brute.found();
  }
  EXPECT_GT(found, rays_.size() / 4);
  const std::vector<std::pair<KdStreamVariant, int>> variants = {
      {KdStreamVariant::PushDown, 4},           {KdStreamVariant::ShortStack, 1},
      {KdStreamVariant::ShortStack, 4},         {KdStreamVariant::ShortStack, 8},
      {KdStreamVariant::PushDownShortStack, 1}, {KdStreamVariant::PushDownShortStack, 8},
      {KdStreamVariant::Stack, 4}};
  for (const auto& [variant, k] : variants) {
    const Traced t = trace(variant, k);
    for (size_t i = 0; i < rays_.size(); ++i) {
      const std::string what = "variant " + std::to_string(int(variant)) + ", " + std::to_string(k) + " entries, ray " +
                               std::to_string(i);
      EXPECT_TRUE(test::sameHit(t.hits[i], restart.hits[i])) << what;
      EXPECT_EQ(t.stats[i].triangleTests, restart.stats[i].triangleTests) << what;
    }
  }
}

TEST_F(KdStreamVariants, PushDownTakesNoMoreStepsThanRestart) {
  const Traced restart = trace(KdStreamVariant::Restart);
  const Traced pushDown = trace(KdStreamVariant::PushDown);
  for (size_t i = 0; i < rays_.size(); ++i) EXPECT_LE(pushDown.stats[i].steps, restart.stats[i].steps) << "ray " << i;
  EXPECT_LT(pushDown.steps, restart.steps);  // and it does skip some
  const Traced shortStack = trace(KdStreamVariant::ShortStack, 1);
  const Traced pushDownShortStack = trace(KdStreamVariant::PushDownShortStack, 1);
  for (size_t i = 0; i < rays_.size(); ++i)
    EXPECT_LE(pushDownShortStack.stats[i].steps, shortStack.stats[i].steps) << "ray " << i;
}

TEST_F(KdStreamVariants, LargerStacksTakeNoMoreSteps) {
  const Traced restart = trace(KdStreamVariant::Restart);
  const Traced one = trace(KdStreamVariant::ShortStack, 1);
  const Traced eight = trace(KdStreamVariant::ShortStack, 8);
  const Traced full = trace(KdStreamVariant::Stack);
  for (size_t i = 0; i < rays_.size(); ++i) {
    EXPECT_LE(one.stats[i].steps, restart.stats[i].steps) << "ray " << i;
    EXPECT_LE(eight.stats[i].steps, one.stats[i].steps) << "ray " << i;
    EXPECT_LE(full.stats[i].steps, eight.stats[i].steps) << "ray " << i;
  }
  // One entry overflows on this tree, and dropping entries costs steps.
  EXPECT_LT(eight.steps, one.steps);
  EXPECT_LT(one.steps, restart.steps);
}

}  // namespace
}  // namespace passtrace
