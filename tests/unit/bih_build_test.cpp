// The BIH build (accel/bih/bih.h): every triangle in exactly one leaf, each
// subtree's triangles within its clip plane, the Config's limits, and
// degenerate inputs (all triangles at one point, one triangle, none).

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "accel/bih/bih.h"
#include "accel/bih/bih_texels.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

// Checks node `index` and returns its subtree's triangles. Every triangle
// below the left child must end at or before the left clip plane, every one
// below the right child start at or after the right one.
std::vector<uint32_t> checkSubtree(const Bih& bih, std::span<const Triangle> tris, uint32_t index, uint32_t depth,
                                   uint32_t& maxDepth) {
  maxDepth = std::max(maxDepth, depth);
  const BihNode& n = bih.nodes.at(index);
  if (n.isLeaf()) return {bih.references.begin() + n.firstRef, bih.references.begin() + n.firstRef + n.refCount};
  EXPECT_LT(n.axis, 3u);
  EXPECT_GT(n.rightChild, index + 1);
  const std::vector<uint32_t> left = checkSubtree(bih, tris, index + 1, depth + 1, maxDepth);
  const std::vector<uint32_t> right = checkSubtree(bih, tris, n.rightChild, depth + 1, maxDepth);
  EXPECT_FALSE(left.empty());
  EXPECT_FALSE(right.empty());
  float leftMax = -kInfinity, rightMin = kInfinity;
  for (uint32_t t : left) {
    EXPECT_LE(tris[t].bounds().max[n.axis], n.clip[0]) << "node " << index;
    leftMax = std::max(leftMax, tris[t].bounds().max[n.axis]);
  }
  for (uint32_t t : right) {
    EXPECT_GE(tris[t].bounds().min[n.axis], n.clip[1]) << "node " << index;
    rightMin = std::min(rightMin, tris[t].bounds().min[n.axis]);
  }
  EXPECT_EQ(leftMax, n.clip[0]) << "the planes are tight";
  EXPECT_EQ(rightMin, n.clip[1]);
  std::vector<uint32_t> all = left;
  all.insert(all.end(), right.begin(), right.end());
  return all;
}

void expectValid(const Bih& bih, std::span<const Triangle> tris, const BihConfig& config) {
  ASSERT_FALSE(bih.nodes.empty());
  uint32_t depth = 0;
  std::vector<uint32_t> all = checkSubtree(bih, tris, 0, 1, depth);
  EXPECT_EQ(depth, bih.depth);
  EXPECT_LE(int(bih.depth), config.maxDepth);
  std::sort(all.begin(), all.end());
  std::vector<uint32_t> expected(tris.size());
  for (uint32_t i = 0; i < tris.size(); ++i) expected[i] = i;
  EXPECT_EQ(all, expected) << "every triangle in exactly one leaf";
  for (const BihNode& n : bih.nodes)
    if (n.isLeaf() && int(n.refCount) > config.leafSize) {
      // Only a depth limit or an unsplittable cell makes a large leaf.
      std::vector<glm::vec3> centroids;
      for (uint32_t r = n.firstRef; r < n.firstRef + n.refCount; ++r)
        centroids.push_back(tris[bih.references[r]].centroid());
      const bool oneCentroid = std::all_of(centroids.begin(), centroids.end(),
                                           [&](const glm::vec3& c) { return c == centroids[0]; });
      EXPECT_TRUE(oneCentroid || int(bih.depth) == config.maxDepth) << n.refCount << " triangles in a leaf";
    }
}

TEST(BihBuild, SphereSoupAndGridsAreValid) {
  const BihConfig config;
  for (const auto& tris : {testmesh::uvSphere(24, 32), testmesh::triangleSoup(3000, Aabb{glm::vec3(-1), glm::vec3(1)},
                                                                              0.1f, 7),
                           testmesh::flatGrid(20, 20), testmesh::degenerateMix(500, 3)}) {
    const Bih bih = buildBih(tris, config);
    expectValid(bih, tris, config);
    EXPECT_GT(bih.nodes.size(), 1u);
  }
}

TEST(BihBuild, ConfigLimitsHold) {
  const auto tris = testmesh::triangleSoup(2000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.05f, 11);
  const BihConfig shallow{.leafSize = 1, .maxDepth = 5};
  const Bih bih = buildBih(tris, shallow);
  expectValid(bih, tris, shallow);
  EXPECT_EQ(bih.depth, 5u);
  const BihConfig big{.leafSize = 64};
  const Bih coarse = buildBih(tris, big);
  expectValid(coarse, tris, big);
  EXPECT_LT(coarse.nodes.size(), buildBih(tris).nodes.size());
}

// The candidate plane halves the global box: two clusters far apart split at
// the scene box's middle on the first level; the planes are the clusters'
// inner faces.
TEST(BihBuild, SplitsTheGlobalBoxNotTheTriangles) {
  std::vector<Triangle> tris;
  for (int i = 0; i < 8; ++i) {
    const float x = i < 4 ? 0.0f : 9.0f;
    const float y = float(i % 4);
    tris.push_back({glm::vec3(x, y, 0), glm::vec3(x + 1, y, 0), glm::vec3(x, y + 1, 0)});
  }
  const Bih bih = buildBih(tris, {.leafSize = 4});
  ASSERT_GE(bih.nodes.size(), 3u);
  EXPECT_EQ(bih.nodes[0].axis, 0u);
  EXPECT_EQ(bih.nodes[0].clip[0], 1.0f);
  EXPECT_EQ(bih.nodes[0].clip[1], 9.0f);
  EXPECT_TRUE(bih.nodes[1].isLeaf());
  EXPECT_TRUE(bih.nodes[bih.nodes[0].rightChild].isLeaf());
}

TEST(BihBuild, AllTrianglesAtOnePointMakeOneLeaf) {
  const Triangle point{glm::vec3(2), glm::vec3(2), glm::vec3(2)};
  const std::vector<Triangle> tris(50, point);
  const Bih bih = buildBih(tris);
  ASSERT_EQ(bih.nodes.size(), 1u);
  EXPECT_TRUE(bih.nodes[0].isLeaf());
  EXPECT_EQ(bih.nodes[0].refCount, 50u);
  EXPECT_EQ(bih.depth, 1u);
}

TEST(BihBuild, CoincidentTrianglesEndAsALeafAfterEmptySplits) {
  // Same centroid, non-zero extent: every halving leaves one side empty.
  const std::vector<Triangle> tris(20, Triangle{glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)});
  const Bih bih = buildBih(tris);
  expectValid(bih, tris, BihConfig{});
  EXPECT_EQ(bih.nodes.size(), 1u);
}

TEST(BihBuild, OneTriangleAndNone) {
  const auto one = testmesh::singleTriangle();
  const Bih bih = buildBih(one);
  ASSERT_EQ(bih.nodes.size(), 1u);
  EXPECT_EQ(bih.nodes[0].refCount, 1u);
  EXPECT_EQ(bih.leafCount(), 1u);
  const Bih none = buildBih({});
  EXPECT_TRUE(none.nodes.empty());
  EXPECT_EQ(none.depth, 0u);
  const BihTexels texels = flattenBih(none, 0);
  EXPECT_TRUE(texels.nodes.empty());
  EXPECT_EQ(texels.floatsPerTriangle, 0.0);
}

TEST(BihBuild, FloatsPerTriangleCountsNodeTexelsAndListEntries) {
  const auto tris = testmesh::uvSphere(12, 16);
  const Bih bih = buildBih(tris);
  const BihTexels texels = flattenBih(bih, tris.size());
  EXPECT_EQ(texels.nodes.size(), bih.nodes.size());
  size_t entries = 0;
  for (const BihNode& n : bih.nodes)
    if (n.isLeaf() && n.refCount > 0) entries += n.refCount + 1;
  EXPECT_EQ(texels.listEntries, entries);
  EXPECT_DOUBLE_EQ(texels.floatsPerTriangle, (4.0 * double(bih.nodes.size()) + double(entries)) / double(tris.size()));
}

}  // namespace
}  // namespace passtrace
