// bvh8 collapsed from the SBVH (--bvh8-builder sbvh, accel/wide_bvh/sbvh_binary_bvh.h):
// the converted binary tree (children after their parent, boxes around their
// children, every part of every finite triangle inside a leaf box that
// references it, no leaf above maxLeafSize), the wide tree (each leaf lists a
// triangle once, at most four packs), its traversals against brute force, and
// its SAH cost against the binned build's where spatial splits pay.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "accel/brute_force.h"
#include "accel/bvh_stack/sbvh_builder.h"
#include "accel/wide_bvh/sbvh_binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_structure.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "tests/bvh_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::contains;
using test::expectTriangleInBoxes;
using test::finiteTriangle;

using testmesh::NamedMesh;

// The converted tree's structure, and where its triangles lie.
void expectValidConversion(const SahBinaryBvh& bvh, std::span<const Triangle> tris, uint32_t maxLeafSize) {
  std::vector<std::vector<Aabb>> leafBoxes(tris.size());
  if (!bvh.nodes.empty()) {
    std::vector<int> reached(bvh.nodes.size(), 0);
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      ASSERT_LT(n, bvh.nodes.size());
      ASSERT_EQ(reached[n]++, 0) << "node " << n;
      const SahBinaryBvhNode& node = bvh.nodes[n];
      if (node.leaf()) {
        EXPECT_LE(node.count, maxLeafSize) << "node " << n;
        ASSERT_LE(node.first + node.count, bvh.prims.size());
        for (uint32_t i = node.first; i < node.first + node.count; ++i)
          leafBoxes.at(bvh.prims[i]).push_back(node.bounds);
        continue;
      }
      for (const uint32_t c : {node.first, node.first + 1}) {
        EXPECT_GT(c, n) << "children come after their parent (the collapse's reverse sweep)";
        ASSERT_LT(c, bvh.nodes.size());
        EXPECT_TRUE(contains(node.bounds, bvh.nodes[c].bounds)) << "node " << c;
        stack.push_back(c);
      }
    }
    EXPECT_EQ(size_t(std::count(reached.begin(), reached.end(), 1)), bvh.nodes.size()) << "every node reached";
  }
  for (size_t t = 0; t < tris.size(); ++t) {
    if (!finiteTriangle(tris[t])) continue;
    ASSERT_FALSE(leafBoxes[t].empty()) << "triangle " << t << " is in no leaf";
    expectTriangleInBoxes(tris[t], leafBoxes[t], t);
  }
}

Aabb laneBox(const WideBvhNode& node, int i) {
  return Aabb{{node.minX[i], node.minY[i], node.minZ[i]}, {node.maxX[i], node.maxY[i], node.maxZ[i]}};
}

// Counts the leaves holding each triangle under `ref`; every lane box inside its parent's.
void countLeaves(const WideBvh& bvh, uint32_t ref, const Aabb& box, std::vector<int>& leaves) {
  if (wideIsLeaf(ref)) {
    std::vector<uint32_t> ids;
    ASSERT_LE(wideLeafPacks(ref), kWideMaxLeafPacks);
    for (uint32_t p = wideLeafFirst(ref); p < wideLeafFirst(ref) + wideLeafPacks(ref); ++p)
      for (const uint32_t id : bvh.packs.at(p).id)
        if (id != kNoHit) ids.push_back(id);
    std::sort(ids.begin(), ids.end());
    EXPECT_TRUE(std::adjacent_find(ids.begin(), ids.end()) == ids.end()) << "a leaf lists a triangle twice";
    for (const uint32_t id : ids) ++leaves.at(id);
    return;
  }
  const WideBvhNode& node = bvh.nodes.at(ref);
  for (int i = 0; i < kWideBvhWidth; ++i) {
    if (node.child[i] == kWideEmpty) continue;
    EXPECT_TRUE(contains(box, laneBox(node, i)));
    countLeaves(bvh, node.child[i], laneBox(node, i), leaves);
  }
}

class WideSbvhMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(WideSbvhMeshTest, ConvertedTreeHoldsEveryPartOfEveryTriangle) {
  const auto& tris = GetParam().tris;
  const SahBuildConfig sah;
  expectValidConversion(buildSbvhBinaryBvh(tris, sah), tris, sah.maxLeafSize);
}

TEST_P(WideSbvhMeshTest, CollapseListsEachTriangleOncePerLeafAndEveryTriangleSomewhere) {
  const auto& tris = GetParam().tris;
  const SahBinaryBvh binary = buildSbvhBinaryBvh(tris);
  const WideBvh bvh = collapseToWideBvh(binary, tris);
  std::vector<int> leaves(tris.size(), 0);
  if (!binary.nodes.empty()) countLeaves(bvh, 0, Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}, leaves);
  size_t stored = 0;
  for (size_t t = 0; t < tris.size(); ++t) {
    stored += size_t(leaves[t]);
    if (finiteTriangle(tris[t])) {
      EXPECT_GE(leaves[t], 1) << "triangle " << t;
    }
  }
  EXPECT_EQ(bvh.references, stored);
}

// The scalar and AVX2 traversals (both triangle tests) and packets of 32 give
// brute force's nearest t and any-hit answer.
TEST_P(WideSbvhMeshTest, TraversalsEqualBruteForce) {
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildSbvhBinaryBvh(tris), tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 150, 23);
  for (const TriangleTest test : {TriangleTest::MollerTrumbore, TriangleTest::Watertight})
    for (const bool anyHit : {false, true})
      for (size_t i = 0; i < rays.size(); ++i) {
        const Hit brute = intersectBruteForce(tris, rays[i], anyHit, nullptr, test);
        const Hit scalar = traverseWideBvhScalar(bvh, tris, rays[i], anyHit, test, nullptr);
        const Hit avx = traverseWideBvhAvx2(bvh, tris, rays[i], anyHit, test, nullptr);
        for (const Hit& h : {scalar, avx}) {
          ASSERT_EQ(h.found(), brute.found()) << "ray " << i << " any hit " << anyHit;
          if (!anyHit && brute.found()) {
            EXPECT_EQ(h.t, brute.t) << "ray " << i;
          }
          if (anyHit && h.found()) {
            EXPECT_LT(h.t, rays[i].tMax) << "ray " << i;
          }
        }
      }
  if (!wideBvhAvx2Available()) return;
  for (const bool anyHit : {false, true})
    for (size_t begin = 0; begin < rays.size(); begin += 32) {
      const size_t count = std::min<size_t>(32, rays.size() - begin);
      std::vector<Hit> hits(count);
      std::vector<RayStats> stats(count);
      traceWideBvhPacketAvx2(bvh, RayPacket::of(std::span<const Ray>(rays.data() + begin, count)), anyHit, hits,
                             stats);
      for (size_t k = 0; k < count; ++k) {
        const Hit brute = intersectBruteForce(tris, rays[begin + k], anyHit);
        ASSERT_EQ(hits[k].found(), brute.found()) << "ray " << begin + k;
        if (!anyHit && brute.found()) {
          EXPECT_EQ(hits[k].t, brute.t) << "ray " << begin + k;
        }
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Meshes, WideSbvhMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()),
                         [](const auto& info) { return info.param.name; });

// Where object splits overlap completely, spatial splits lower the SAH cost of
// the tree the collapse takes (references grow, within the budget of 2x).
TEST(WideSbvh, SahCostOnLongThinTrianglesAtMostTheBinnedBuilds) {
  const std::vector<Triangle> tris = testmesh::longThinTriangles(400, 3);
  const SahBuildConfig sah;
  const SahBinaryBvh sbvh = buildSbvhBinaryBvh(tris, sah);
  const SahBinaryBvh binned = buildBinnedSahBvh(tris, sah);
  expectValidConversion(sbvh, tris, sah.maxLeafSize);
  EXPECT_GT(sbvh.prims.size(), tris.size()) << "spatial splits happened";
  EXPECT_LE(double(sbvh.prims.size()), (1.0 + wideSbvhConfig(sah).sbvhSplitBudget) * double(tris.size()));
  const double sbvhCost = bvhSahCost(sbvh, sah), binnedCost = bvhSahCost(binned, sah);
  EXPECT_LE(sbvhCost, binnedCost);
  EXPECT_LT(sbvhCost, 0.8 * binnedCost) << "sbvh " << sbvhCost << " binned " << binnedCost;
}

// Two SBVH leaves holding the two parts of the same two triangles: the
// collapse merges them (4 references, one pack) and keeps each triangle once.
TEST(WideSbvh, MergedLeavesListASharedTriangleOnce) {
  const std::vector<Triangle> tris = {
      {glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 1, 0)},
      {glm::vec3(0, 0, 1), glm::vec3(2, 0, 1), glm::vec3(0, 1, 1)}};
  BinaryBvh split;
  split.bounds = testmesh::boundsOf(tris);
  split.references = {0, 1, 1, 0};
  BvhStackNode root;
  root.child[0] = BvhChild{Aabb{glm::vec3(0, 0, 0), glm::vec3(1, 1, 1)}, 0, 2};
  root.child[1] = BvhChild{Aabb{glm::vec3(1, 0, 0), glm::vec3(2, 0.5f, 1)}, 2, 2};
  split.nodes.push_back(root);
  split.leaves = 2, split.depth = 2;
  const WideBvh bvh = collapseToWideBvh(toSahBinaryBvh(split, 8), tris);
  std::vector<int> leaves(tris.size(), 0);
  countLeaves(bvh, 0, Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}, leaves);
  EXPECT_EQ(leaves, (std::vector<int>{1, 1}));
  EXPECT_EQ(bvh.references, 2u);
  RayStats stats;
  const Ray ray{glm::vec3(0.5f, 0.2f, 2.0f), glm::vec3(0, 0, -1)};
  EXPECT_EQ(traverseWideBvhScalar(bvh, tris, ray, false, TriangleTest::MollerTrumbore, &stats).id, 1u);
  EXPECT_EQ(stats.triangleTests, 2u) << "each triangle tested once";
}

// The wide leaf sizes reach the SBVH builder (leaves of up to maxLeafSize).
TEST(WideSbvh, ConfigTakesTheWideBvhsLeafSizesAndCosts) {
  SahBuildConfig sah;
  sah.leafSize = 3, sah.maxLeafSize = 6, sah.bins = 16, sah.traversalCost = 2.0f, sah.intersectionCost = 0.5f;
  const BvhStackConfig c = wideSbvhConfig(sah);
  EXPECT_EQ(c.leafSize, 3u);
  EXPECT_EQ(c.maxLeafSize, 6u);
  EXPECT_EQ(c.bins, 16u);
  EXPECT_EQ(c.traversalCost, 2.0f);
  EXPECT_EQ(c.intersectionCost, 0.5f);
}

// A leaf above maxLeafSize (what the SBVH leaves at its depth limit) is cut
// into halves under its box, so the collapse never needs more than four packs.
TEST(WideSbvh, OversizedLeavesAreCutToFitAWideLeaf) {
  const std::vector<Triangle> tris = testmesh::triangleSoup(40, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, 0.1f, 7);
  BinaryBvh lone;
  lone.bounds = testmesh::boundsOf(tris);
  for (uint32_t i = 0; i < tris.size(); ++i) lone.references.push_back(i);
  BvhStackNode root;
  root.child[0] = BvhChild{lone.bounds, 0, uint32_t(tris.size())};
  root.child[1].present = false;
  lone.nodes.push_back(root);
  lone.leaves = 1, lone.depth = 1;
  const SahBinaryBvh binary = toSahBinaryBvh(lone, 8);
  expectValidConversion(binary, tris, 8);
  const WideBvh bvh = collapseToWideBvh(binary, tris);
  std::vector<int> leaves(tris.size(), 0);
  countLeaves(bvh, 0, Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}, leaves);
  for (size_t t = 0; t < tris.size(); ++t) EXPECT_EQ(leaves[t], 1) << "triangle " << t;
  const std::vector<Ray> rays = testmesh::rayMix(lone.bounds, 50, 3);
  for (size_t i = 0; i < rays.size(); ++i)
    EXPECT_EQ(traverseWideBvhScalar(bvh, tris, rays[i], false, TriangleTest::MollerTrumbore, nullptr).t,
              intersectBruteForce(tris, rays[i], false).t)
        << "ray " << i;
}

// The registry rows build from the SBVH when asked: more references than
// triangles on long thin triangles (the binned build stores each once).
TEST(WideSbvh, Bvh8RowsReadTheBuilder) {
  const std::vector<Triangle> tris = testmesh::longThinTriangles(400, 5);
  AccelBuildConfig config;
  EXPECT_EQ(makeBvh8Cpu(tris, config)->stats().references, tris.size());
  config.bvh8Builder = Bvh8BuilderKind::Sbvh;
  for (const auto& accel : {makeBvh8Cpu(tris, config), makeBvh8PacketCpu(tris, config)}) {
    EXPECT_GT(accel->stats().references, tris.size()) << accel->name();
    EXPECT_GT(accel->stats().sahCost, 0.0);
  }
}

}  // namespace
}  // namespace passtrace
