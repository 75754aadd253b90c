// Kay/Kajiya BVH construction: valid binary trees, the child-swap
// probability, degenerate and coincident input, the split-axis rule, the
// thesis's floats per triangle, determinism, and the build configuration
// reaching the builder through the accelerator.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/cpu_accelerator.h"
#include "tests/bvh_checks.h"
#include "tests/hit_checks.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::expectValidBvh;
using test::tiedT;
using testmesh::NamedMesh;

// --- per mesh -----------------------------------------------------------------

class KayKajiyaMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KayKajiyaMeshTest, TreeIsValidBinaryAndCountsAddUp) {
  const auto& tris = GetParam().tris;
  const Bvh bvh = buildKayKajiya(tris);
  expectValidBvh(bvh, tris);
  EXPECT_EQ(bvh.leafCount(), tris.size());
  EXPECT_EQ(bvh.internalCount(), tris.size() - 1);
  for (const BvhNode& n : bvh.nodes) EXPECT_TRUE(n.isLeaf() || n.childCount == 2);
}

TEST_P(KayKajiyaMeshTest, SwapProbabilityChangesChildOrderButNeverAHit) {
  const auto& tris = GetParam().tris;
  const Bvh keep = buildKayKajiya(tris, {.swapProbability = 0.0f, .seed = 3});
  const Bvh swap = buildKayKajiya(tris, {.swapProbability = 1.0f, .seed = 3});
  // Same partition, children reversed at every internal node.
  ASSERT_EQ(keep.nodes.size(), swap.nodes.size());
  for (size_t n = 0; n < keep.nodes.size(); ++n) {
    EXPECT_EQ(keep.nodes[n].box.min, swap.nodes[n].box.min);
    EXPECT_EQ(keep.nodes[n].triangle, swap.nodes[n].triangle);
    if (keep.nodes[n].isLeaf()) continue;
    const uint32_t f = keep.nodes[n].firstChild;
    EXPECT_EQ(keep.children[f], swap.children[f + 1]);
    EXPECT_EQ(keep.children[f + 1], swap.children[f]);
    EXPECT_LT(keep.children[f], keep.children[f + 1]) << "p = 0 keeps the left (below median) child first";
  }
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 5);
  const EscapeSequence a = flattenEscapeSequence(keep, tris), b = flattenEscapeSequence(swap, tris);
  size_t differ = 0;
  for (const Ray& ray : rays) {
    const Hit ha = traverseEscapeSequence(a, ray, false), hb = traverseEscapeSequence(b, ray, false);
    ASSERT_EQ(ha.found(), hb.found());
    if (ha.id != hb.id) {
      EXPECT_TRUE(tiedT(ha.t, hb.t));
    }
    differ += ha.id != hb.id;
  }
  EXPECT_LT(differ, rays.size() / 10);
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, KayKajiyaMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()), meshName);

// --- construction ----------------------------------------------------------------

TEST(KayKajiyaBvh, EmptySceneGivesEmptyTreeAndNoHits) {
  const std::vector<Triangle> none;
  const Bvh bvh = buildKayKajiya(none);
  EXPECT_TRUE(bvh.empty());
  EXPECT_EQ(bvh.depth(), 0u);
  const EscapeSequence seq = flattenEscapeSequence(bvh, none);
  EXPECT_TRUE(seq.texels.empty());
  EXPECT_EQ(seq.floatsPerTriangle(), 0.0f);
  RayStats stats;
  EXPECT_FALSE(traverseEscapeSequence(seq, Ray{}, false, &stats).found());
  EXPECT_FALSE(traverseBvhRecursive(bvh, none, Ray{}, false, &stats).found());
  EXPECT_EQ(stats.steps, 0u);
}

TEST(KayKajiyaBvh, SingleTriangleIsALeafRoot) {
  const auto tris = testmesh::singleTriangle();
  const Bvh bvh = buildKayKajiya(tris);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_TRUE(bvh.nodes[0].isLeaf());
  EXPECT_EQ(bvh.nodes[0].triangle, 0u);
  EXPECT_EQ(bvh.depth(), 1u);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  ASSERT_EQ(seq.texels.size(), 3u);
  EXPECT_EQ(seq.texels[0], glm::vec4(tris[0].v0, -1.0f));
  EXPECT_EQ(seq.texels[1], glm::vec4(tris[0].v1, packIndex(0)));
  EXPECT_EQ(seq.texels[2], glm::vec4(tris[0].v2, 0.0f));
  EXPECT_EQ(seq.floatsPerTriangle(), 0.0f);
  const Ray ray{glm::vec3(-0.5f, -0.5f, 2.0f), glm::vec3(0, 0, -1)};
  RayStats stats;
  const Hit hit = traverseEscapeSequence(seq, ray, false, &stats);
  EXPECT_EQ(hit.id, 0u);
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  EXPECT_EQ(stats.steps, 1u);
  EXPECT_EQ(stats.triangleTests, 1u);
}

TEST(KayKajiyaBvh, AllTrianglesAtOnePointStillBuildBalanced) {
  for (const size_t n : {2u, 3u, 1000u, 4096u}) {
    const auto tris = testmesh::pointMesh(n);
    const Bvh bvh = buildKayKajiya(tris, {.swapProbability = 0.0f});
    expectValidBvh(bvh, tris);
    // Halving by index gives a balanced tree: ceil(log2 n) + 1 levels.
    EXPECT_EQ(bvh.depth(), static_cast<uint32_t>(std::ceil(std::log2(double(n)))) + 1) << n;
    // Halving keeps scene order: without swaps, leaves appear in index order.
    const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
    uint32_t expected = 0;
    for (size_t i = 0; i < seq.texels.size();) {
      if (seq.texels[i].w >= 0.0f) {
        i += 2;
        continue;
      }
      EXPECT_EQ(unpackIndex(seq.texels[i + 1].w), expected++);
      i += 3;
    }
    // Degenerate triangles are never hit.
    const Ray ray{glm::vec3(0.5f, 0.5f, -1.0f), glm::vec3(0, 0, 1)};
    EXPECT_FALSE(traverseEscapeSequence(seq, ray, false).found());
  }
}

TEST(KayKajiyaBvh, CoincidentCentroidsFallBackToHalving) {
  const auto tris = testmesh::coincidentCentroids(1000, 1);
  const glm::vec3 c = tris[0].centroid();
  for (const Triangle& t : tris) ASSERT_EQ(t.centroid(), c) << "the mesh must really be coincident";
  const Bvh bvh = buildKayKajiya(tris);
  expectValidBvh(bvh, tris);
  EXPECT_EQ(bvh.depth(), 11u);  // ceil(log2 1000) + 1
}

TEST(KayKajiyaBvh, SplitsOnTheAxisWithTheSmallestChildArea) {
  // Two columns of thin triangles, separated along x, each tall along y: the
  // y median cuts every column in two halves of full width (large area),
  // the x median separates the columns (small area).
  std::vector<Triangle> tris;
  for (int column = 0; column < 2; ++column)
    for (int k = 0; k < 8; ++k) {
      const float x = column * 10.0f, y = k * 1.0f;
      tris.push_back({glm::vec3(x, y, 0), glm::vec3(x + 0.5f, y, 0), glm::vec3(x, y + 0.9f, 0)});
    }
  const Bvh bvh = buildKayKajiya(tris, {.swapProbability = 0.0f});
  const BvhNode& root = bvh.nodes[0];
  ASSERT_EQ(root.childCount, 2u);
  const Aabb& left = bvh.nodes[bvh.children[root.firstChild]].box;
  const Aabb& right = bvh.nodes[bvh.children[root.firstChild + 1]].box;
  EXPECT_EQ(left.max.x, 0.5f);
  EXPECT_EQ(right.min.x, 10.0f);
}

TEST(KayKajiyaBvh, FloatsPerTriangleMatchesThesisTable3) {
  // Thesis Table 3: K/K uses 8 floats per triangle, 7.8 on the 32-triangle
  // Cornell box: a binary tree has N - 1 boxes of 8 floats, 8 (N - 1) / N.
  const auto tris = testmesh::triangleSoup(32, Aabb{glm::vec3(0), glm::vec3(1)}, 0.2f, 1);
  const EscapeSequence seq = flattenEscapeSequence(buildKayKajiya(tris), tris);
  EXPECT_EQ(seq.boxCount, 31u);
  EXPECT_EQ(seq.triangleCount, 32u);
  EXPECT_FLOAT_EQ(seq.floatsPerTriangle(), 7.75f);
  for (const NamedMesh& mesh : testmesh::standardMeshes()) {
    const float n = static_cast<float>(mesh.tris.size());
    EXPECT_FLOAT_EQ(flattenEscapeSequence(buildKayKajiya(mesh.tris), mesh.tris).floatsPerTriangle(),
                    8.0f * (n - 1.0f) / n)
        << mesh.name;
  }
}

TEST(KayKajiyaBvh, DeterministicForASeed) {
  const auto tris = testmesh::triangleSoup(5000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 21);
  const Bvh a = buildKayKajiya(tris, {.swapProbability = 0.5f, .seed = 1234});
  const Bvh b = buildKayKajiya(tris, {.swapProbability = 0.5f, .seed = 1234});
  const Bvh c = buildKayKajiya(tris, {.swapProbability = 0.5f, .seed = 4321});
  EXPECT_EQ(a.children, b.children);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t n = 0; n < a.nodes.size(); ++n) {
    EXPECT_EQ(a.nodes[n].triangle, b.nodes[n].triangle);
    EXPECT_EQ(a.nodes[n].box.min, b.nodes[n].box.min);
    EXPECT_EQ(a.nodes[n].box.max, b.nodes[n].box.max);
  }
  EXPECT_NE(a.children, c.children) << "another seed flips other coins";
  const EscapeSequence sa = flattenEscapeSequence(a, tris), sb = flattenEscapeSequence(b, tris);
  EXPECT_EQ(sa.texels, sb.texels);
  // Roughly half of the internal nodes have swapped children (left has the lower index).
  size_t swapped = 0;
  for (const BvhNode& n : a.nodes)
    if (!n.isLeaf()) swapped += a.children[n.firstChild] > a.children[n.firstChild + 1];
  EXPECT_NEAR(double(swapped) / double(a.internalCount()), 0.5, 0.05);
}

// --- the accelerator interface -------------------------------------------------

TEST(CpuAccelerator, BuildConfigReachesTheBuilder) {
  const auto tris = testmesh::triangleSoup(500, Aabb{glm::vec3(0), glm::vec3(1)}, 0.2f, 2);
  AccelBuildConfig keep, swap;
  keep.kayKajiya.swapProbability = 0.0f;
  swap.kayKajiya.swapProbability = 1.0f;
  const auto a = testing_registry::cpuStructure(0, tris, keep), b = testing_registry::cpuStructure(0, tris, swap);
  // Same tree, other order: a ray hitting several triangles visits them differently.
  uint64_t stepsA = 0, stepsB = 0;
  for (const Ray& ray : testmesh::makeRays(testmesh::RayKind::OutsideIn, testmesh::boundsOf(tris), 200, 9)) {
    RayStats sa, sb;
    const Hit ha = a->intersect(ray, false, &sa), hb = b->intersect(ray, false, &sb);
    EXPECT_EQ(ha.found(), hb.found());
    stepsA += sa.steps;
    stepsB += sb.steps;
  }
  EXPECT_NE(stepsA, stepsB);
}

}  // namespace
}  // namespace passtrace
