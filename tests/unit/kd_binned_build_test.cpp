// The binned SAH kd builder, the seed's termination rules, the SAH cost
// statistic and the parallel build: binned trees pass the exact builder's
// structural and completeness checks (degenerate scenes too), papay's limits
// hold, the cost matches a tree worked out by hand, and both builders give
// the same tree on one thread and on several.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "accel/kd/kd_binned_builder.h"
#include "accel/kd/kd_build_driver.h"
#include "accel/kd/kd_sah_cost.h"
#include "accel/kd/kd_structures.h"
#include "accel/kd/kd_termination.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/registry.h"
#include "tests/kd_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;
using test::kd::expectMinElements;
using test::kd::expectValidKdTree;
using test::kd::kdMeshes;

AccelBuildConfig binned(KdTermination rule = KdTermination::Thesis) {
  AccelBuildConfig config;
  config.kdBuilder = KdBuilderKind::Binned;
  config.kdTermination = rule;
  return config;
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

class KdBinnedMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdBinnedMeshTest, TreesAreValidAndCompleteUnderBothRules) {
  const auto& tris = GetParam().tris;
  const KdTree thesis = buildKdTreeFor(tris, binned());
  expectValidKdTree(thesis, tris, GetParam().name + " binned thesis");
  EXPECT_LE(thesis.depth(), static_cast<uint32_t>(kdDefaultMaxDepth(tris.size())) + 1);
  expectMinElements(thesis, 2);
  const KdTree papay = buildKdTreeFor(tris, binned(KdTermination::Papay));
  expectValidKdTree(papay, tris, GetParam().name + " binned papay");
  EXPECT_LE(papay.depth(), static_cast<uint32_t>(kdPapayMaxDepth(tris.size())) + 1);
  expectMinElements(papay, kdPapayLeafBelow(tris.size()) - 1);
}

INSTANTIATE_TEST_SUITE_P(Meshes, KdBinnedMeshTest, ::testing::ValuesIn(kdMeshes()), meshName);

TEST(KdBinned, MaxDepthAndMinElementsAreRespected) {
  const auto tris = testmesh::triangleSoup(4000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 8);
  for (const int depth : {1, 3, 6, 12}) {
    KdBuildConfig config;
    config.maxDepth = depth;
    const KdTree tree = buildKdTreeBinned(tris, config);
    EXPECT_LE(tree.depth(), static_cast<uint32_t>(depth) + 1);
    if (depth <= 6) {
      EXPECT_EQ(tree.depth(), static_cast<uint32_t>(depth) + 1) << "a soup splits as deep as allowed";
    }
    expectValidKdTree(tree, tris, "maxDepth " + std::to_string(depth));
  }
  for (const int minElements : {1, 2, 8, 50}) {
    KdBuildConfig config;
    config.minElements = minElements;
    const KdTree tree = buildKdTreeBinned(tris, config);
    expectMinElements(tree, static_cast<size_t>(minElements));
    expectValidKdTree(tree, tris, "minElements " + std::to_string(minElements));
  }
}

TEST(KdBinned, DegenerateScenesBuild) {
  const auto points = testmesh::pointMesh(1000);  // a point voxel: one leaf
  const KdTree pointTree = buildKdTreeBinned(points);
  ASSERT_EQ(pointTree.nodes.size(), 1u);
  EXPECT_EQ(pointTree.nodes[0].refCount, 1000u);
  std::vector<Triangle> line, dups;
  for (int i = 0; i < 300; ++i) {
    const float x = float(i % 17) * 0.1f;
    line.push_back({glm::vec3(x, 1, 2), glm::vec3(x + 0.3f, 1, 2), glm::vec3(x + 0.1f, 1, 2)});
    dups.push_back({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)});
  }
  expectValidKdTree(buildKdTreeBinned(line), line, "line");
  const KdTree tree = buildKdTreeBinned(dups);
  expectValidKdTree(tree, dups, "duplicates");
  const Hit hit = traverseKdTree(tree, dups, Ray{glm::vec3(0.2f, 0.2f, 1), glm::vec3(0, 0, -1)}, false);
  EXPECT_TRUE(hit.found());
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  const auto mix = testmesh::degenerateMix(2000, 5);
  expectValidKdTree(buildKdTreeBinned(mix), mix, "degenerate mix");
}

// Two flat grids 1e-6 apart in a scene of diagonal about 3.5: no plane may
// cut between them (minVoxelFraction), whichever builder.
TEST(KdBinned, NoVoxelThinnerThanTheMinimum) {
  std::vector<Triangle> tris = testmesh::triangleSoup(500, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.2f, 3);
  for (const float z : {0.3f, 0.300001f}) {
    const auto grid = testmesh::flatGrid(8, 8, 2, z);
    tris.insert(tris.end(), grid.begin(), grid.end());
  }
  for (const KdBuilderKind kind : {KdBuilderKind::Exact, KdBuilderKind::Binned}) {
    AccelBuildConfig config;
    config.kdBuilder = kind;
    const KdTree tree = buildKdTreeFor(tris, config);
    expectValidKdTree(tree, tris, "thin");
    const float minThickness = KdBuildConfig{}.minVoxelFraction * glm::length(tree.bounds.extent());
    for (const KdNode& n : tree.nodes) {
      if (n.isLeaf()) continue;
      EXPECT_GE(n.split - n.box.min[n.axis], minThickness);
      EXPECT_GE(n.box.max[n.axis] - n.split, minThickness);
    }
  }
}

TEST(KdTermination, PapayLimitsByHand) {
  EXPECT_EQ(kdPapayMaxDepth(0), 2);
  EXPECT_EQ(kdPapayMaxDepth(1), 2);
  EXPECT_EQ(kdPapayMaxDepth(2), 4);          // 3.2
  EXPECT_EQ(kdPapayMaxDepth(1000), 14);      // 2 + 11.96
  EXPECT_EQ(kdPapayMaxDepth(4000), 17);      // 2 + 14.36
  EXPECT_EQ(kdPapayMaxDepth(100000), 22);    // 2 + 19.93
  EXPECT_EQ(kdPapayMaxDepth(1000000), 26);   // 2 + 23.92
  EXPECT_EQ(kdPapayLeafBelow(1000), 2u);
  EXPECT_EQ(kdPapayLeafBelow(699'999), 2u);
  EXPECT_EQ(kdPapayLeafBelow(700'000), 8u);
  EXPECT_EQ(kdPapayLeafBelow(3'000'000), 8u);
  EXPECT_EQ(kdPapayLeafBelow(3'000'001), 12u);
  // Papay's rules replace -e and -d; thesis keeps them.
  const KdBuildConfig given{.maxDepth = 5, .minElements = 40};
  const KdBuildConfig papay = kdWithTermination(given, KdTermination::Papay, 4000);
  EXPECT_EQ(papay.maxDepth, 17);
  EXPECT_EQ(papay.minElements, 1);
  EXPECT_EQ(kdWithTermination(given, KdTermination::Papay, 1'000'000).minElements, 7);
  EXPECT_EQ(kdWithTermination(given, KdTermination::Papay, 5'000'000).minElements, 11);
  EXPECT_EQ(kdWithTermination(given, KdTermination::Thesis, 4000).maxDepth, 5);
  EXPECT_EQ(kdWithTermination(given, KdTermination::Thesis, 4000).minElements, 40);
}

// 4000 triangles in eight nested clusters (each a quarter of the last's
// size, in its corner): d_max = 17, so no leaf deeper than 18 levels, where
// the same builder without a depth limit goes deeper; n_max = 2, so no node
// of one triangle is split.
TEST(KdTermination, PapayTreesKeepTheirLimits) {
  std::vector<Triangle> tris;
  for (int k = 0; k < 8; ++k) {
    const float size = std::pow(0.25f, float(k));
    const auto cluster = testmesh::triangleSoup(500, Aabb{glm::vec3(0), glm::vec3(size)}, 0.02f * size, 21 + k);
    tris.insert(tris.end(), cluster.begin(), cluster.end());
  }
  for (const KdBuilderKind kind : {KdBuilderKind::Exact, KdBuilderKind::Binned}) {
    AccelBuildConfig config;
    config.kdBuilder = kind;
    config.kdTermination = KdTermination::Papay;
    const KdTree papay = buildKdTreeFor(tris, config);
    expectValidKdTree(papay, tris, "papay");
    EXPECT_LE(papay.depth(), 18u);
    expectMinElements(papay, 1);
    const KdBuildConfig unlimited{.maxDepth = kKdDepthLimit, .minElements = 1};
    const KdTree deep = kind == KdBuilderKind::Exact ? buildKdTree(tris, unlimited) : buildKdTreeBinned(tris, unlimited);
    EXPECT_GT(deep.depth(), 18u) << "the limit binds";
  }
}

// Root [0,2]x[0,1]x[0,1] (area 10) split at x = 1 into two unit cubes (area
// 6 each) holding 2 and 1 references: 1 + 1.5 * 2 * 0.6 + 1.5 * 1 * 0.6 = 3.7.
TEST(KdSahCost, HandBuiltTree) {
  KdTree tree;
  tree.bounds = Aabb{glm::vec3(0), glm::vec3(2, 1, 1)};
  KdNode root;
  root.axis = 0, root.split = 1.0f, root.rightChild = 2, root.box = tree.bounds;
  KdNode left, right;
  left.parent = right.parent = 0;
  left.box = Aabb{glm::vec3(0), glm::vec3(1)};
  right.box = Aabb{glm::vec3(1, 0, 0), glm::vec3(2, 1, 1)};
  left.firstRef = 0, left.refCount = 2;
  right.firstRef = 2, right.refCount = 1;
  tree.nodes = {root, left, right};
  tree.references = {0, 1, 1};
  EXPECT_NEAR(kdSahCost(tree, 1.0, 1.5), 3.7, 1e-9);
  EXPECT_NEAR(kdSahCost(tree, 2.0, 1.0), 2.0 + 1.2 + 0.6, 1e-9);
  // A single leaf of N costs K_I N; an empty tree nothing.
  tree.nodes = {KdNode{.refCount = 7, .box = tree.bounds}};
  EXPECT_NEAR(kdSahCost(tree, 1.0, 1.5), 10.5, 1e-9);
  EXPECT_EQ(kdSahCost(KdTree{}, 1.0, 1.5), 0.0);
}

// The kd rows report the cost of the tree they built and its bytes.
TEST(KdSahCost, KdRowsReportCostAndBytes) {
  const auto tris = testmesh::triangleSoup(3000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 4);
  for (const AccelBuildConfig& config : {AccelBuildConfig{}, binned(), binned(KdTermination::Papay)}) {
    const KdTree tree = buildKdTreeFor(tris, config);
    const AccelStats s = makeCpuStructure("kd-tree", tris, config)->stats();
    EXPECT_NEAR(s.sahCost, kdSahCost(tree, 1.0, 1.5), 1e-6 * s.sahCost);
    EXPECT_GT(s.sahCost, 0.0);
    EXPECT_LT(s.sahCost, 1.5 * 3000);
    EXPECT_EQ(s.structureBytes, tree.nodes.size() * sizeof(KdNode) + tree.references.size() * sizeof(uint32_t));
    const AccelStats restart = makeCpuStructure("kd-restart", tris, config)->stats();
    EXPECT_EQ(restart.sahCost, s.sahCost);
    EXPECT_GT(restart.structureBytes, 0u);
  }
}

// Large enough for parallel subtrees and parallel sweeps at the top
// (kKdParallelSweepRefs): the same nodes and references on 1 and 2 threads.
TEST(KdParallelBuild, SameTreeForAnyThreadCount) {
  const auto tris = testmesh::triangleSoup(70'000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.02f, 77);
  for (const KdBuilderKind kind : {KdBuilderKind::Exact, KdBuilderKind::Binned}) {
    AccelBuildConfig config;
    config.kdBuilder = kind;
    KdTree trees[2];
    for (const int threads : {1, 2}) {
      tbb::task_arena arena(threads);
      arena.execute([&] { trees[threads - 1] = buildKdTreeFor(tris, config); });
    }
    const KdTree &a = trees[0], &b = trees[1];
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_GT(a.nodes.size(), 2 * tris.size() / kKdParallelNodeRefs) << "big enough to build in parallel";
    EXPECT_EQ(a.references, b.references);
    size_t differing = 0;
    for (size_t i = 0; i < a.nodes.size(); ++i) {
      const KdNode &x = a.nodes[i], &y = b.nodes[i];
      differing += x.axis != y.axis || x.split != y.split || x.rightChild != y.rightChild || x.parent != y.parent ||
                   x.firstRef != y.firstRef || x.refCount != y.refCount || x.box.min != y.box.min ||
                   x.box.max != y.box.max;
    }
    EXPECT_EQ(differing, 0u);
    expectValidKdTree(a, tris, "parallel");
  }
}

}  // namespace
}  // namespace passtrace
