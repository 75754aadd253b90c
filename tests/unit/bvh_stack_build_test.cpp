// The stack BVH's three builders (accel/bvh_stack/): every finite triangle
// referenced, every node reached once, boxes containing their children and
// their references (for the SBVH's clipped references: points sampled over
// each triangle lie in a leaf box that references it), the SBVH's spatial
// splits on long thin triangles, and each build's traversal against brute force.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/bvh_stack/bvh_stack_structure.h"
#include "accel/bvh_stack/bvh_stack_traversal.h"
#include "accel/bvh_stack/sbvh_builder.h"
#include "accel/reference_lists.h"
#include "tests/hit_checks.h"
#include "tests/bvh_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::contains;
using test::expectTriangleInBoxes;
using test::finiteTriangle;

constexpr BvhBuilderKind kBuilders[] = {BvhBuilderKind::Sah, BvhBuilderKind::Sbvh, BvhBuilderKind::Middle};

using testmesh::longThinTriangles;

// Structural checks of one build.
void expectValid(const BinaryBvh& bvh, std::span<const Triangle> tris, bool clipped) {
  const BvhStackConfig config;
  size_t finite = 0;
  for (const Triangle& t : tris) finite += finiteTriangle(t);
  if (finite == 0) {
    EXPECT_TRUE(bvh.empty());
    return;
  }
  ASSERT_FALSE(bvh.empty());
  std::vector<int> nodeSeen(bvh.nodes.size(), 0);
  std::vector<std::vector<Aabb>> leafBoxes(tris.size());  // per triangle: the leaves referencing it
  std::vector<std::pair<uint32_t, Aabb>> stack{{0u, bvh.bounds}};
  size_t leaves = 0, references = 0;
  while (!stack.empty()) {
    const auto [index, box] = stack.back();
    stack.pop_back();
    ASSERT_LT(index, bvh.nodes.size());
    ++nodeSeen[index];
    for (const BvhChild& c : bvh.nodes[index].child) {
      if (!c.present) continue;
      EXPECT_TRUE(contains(box, c.box)) << "node " << index;
      if (!c.isLeaf()) {
        stack.emplace_back(c.index, c.box);
        continue;
      }
      ++leaves;
      references += c.count;
      ASSERT_LE(size_t(c.index) + c.count, bvh.references.size());
      for (uint32_t j = c.index; j < c.index + c.count; ++j) {
        const uint32_t t = bvh.references[j];
        ASSERT_LT(t, tris.size());
        leafBoxes[t].push_back(c.box);
        if (!clipped) EXPECT_TRUE(contains(c.box, tris[t].bounds())) << "triangle " << t;
      }
    }
  }
  for (int seen : nodeSeen) EXPECT_EQ(seen, 1);
  EXPECT_EQ(leaves, bvh.leaves);
  EXPECT_EQ(references, bvh.references.size());
  EXPECT_LE(bvh.depth, config.maxDepth);
  for (size_t t = 0; t < tris.size(); ++t) {
    if (!finiteTriangle(tris[t])) continue;
    ASSERT_FALSE(leafBoxes[t].empty()) << "triangle " << t << " is in no leaf";
    if (!clipped) {
      EXPECT_EQ(leafBoxes[t].size(), 1u) << "triangle " << t;
      continue;
    }
    // Every sampled point of the triangle lies in one of its leaves' boxes.
    expectTriangleInBoxes(tris[t], leafBoxes[t], t);
  }
}

TEST(BvhStackBuild, EveryBuilderMakesAValidTreeOnTheStandardMeshes) {
  for (const testmesh::NamedMesh& mesh : testmesh::standardMeshes())
    for (const BvhBuilderKind b : kBuilders) {
      SCOPED_TRACE(mesh.name + " " + std::string(kBvhBuilderNames[int(b)]));
      expectValid(buildBvhStackTree(mesh.tris, b), mesh.tris, b == BvhBuilderKind::Sbvh);
    }
}

TEST(BvhStackBuild, SbvhSplitsLongThinTrianglesSpatiallyAndLowersTheSahCost) {
  const std::vector<Triangle> tris = longThinTriangles(400, 3);
  const BvhStackConfig config;
  const BinaryBvh sah = buildBvhStackTree(tris, BvhBuilderKind::Sah);
  const BinaryBvh sbvh = buildBvhStackTree(tris, BvhBuilderKind::Sbvh);
  expectValid(sbvh, tris, true);
  EXPECT_GT(sbvh.references.size(), tris.size());  // spatial splits happened
  EXPECT_LE(double(sbvh.references.size()), (1.0 + config.sbvhSplitBudget) * double(tris.size()));
  EXPECT_LT(binaryBvhSahCost(sbvh, config.traversalCost, config.intersectionCost),
            binaryBvhSahCost(sah, config.traversalCost, config.intersectionCost));
}

TEST(BvhStackBuild, SplitReferenceBoundsBothPartsOfTheTriangle) {
  const Triangle tri{glm::vec3(0.0f), glm::vec3(4.0f, 0.0f, 0.0f), glm::vec3(0.0f, 2.0f, 0.0f)};
  Aabb below, above;
  splitReference(tri, BvhBuildRef{tri.bounds(), 0}, 0, 1.0f, below, above);
  EXPECT_FLOAT_EQ(below.max.x, 1.0f);
  EXPECT_FLOAT_EQ(above.min.x, 1.0f);
  EXPECT_FLOAT_EQ(above.max.x, 4.0f);
  EXPECT_NEAR(below.max.y, 2.0f, 1e-5f);
  EXPECT_NEAR(above.max.y, 1.5f, 1e-5f);  // the hypotenuse crosses x = 1 at y = 1.5
  // A plane beyond the triangle leaves one part empty.
  splitReference(tri, BvhBuildRef{tri.bounds(), 0}, 0, 5.0f, below, above);
  EXPECT_TRUE(above.empty());
  EXPECT_TRUE(contains(below, tri.bounds()));
}

TEST(BvhStackBuild, EveryBuildTracesAsBruteForce) {
  std::vector<testmesh::NamedMesh> meshes = testmesh::standardMeshes();
  meshes.push_back({"longThin", longThinTriangles(400, 5)});
  for (const testmesh::NamedMesh& mesh : meshes)
    for (const BvhBuilderKind b : kBuilders) {
      SCOPED_TRACE(mesh.name + " " + std::string(kBvhBuilderNames[int(b)]));
      AccelBuildConfig config;
      config.bvhBuilder = b;
      const auto accel = makeBvhStackCpu(mesh.tris, config);
      for (const Ray& ray : testmesh::rayMix(testmesh::boundsOf(mesh.tris), 100, 17))
        for (const bool anyHit : {false, true}) {
          const Hit want = intersectBruteForce(mesh.tris, ray, anyHit, nullptr, TriangleTest::MollerTrumbore);
          const Hit got = accel->intersect(ray, anyHit, nullptr);
          ASSERT_EQ(got.found(), want.found());
          if (!anyHit && got.found() && got.id != want.id) EXPECT_TRUE(test::tiedT(got.t, want.t));
        }
    }
}

TEST(BvhStackBuild, StatsCountTheTree) {
  const testmesh::NamedMesh sphere = testmesh::standardMeshes().front();
  for (const BvhBuilderKind b : kBuilders) {
    AccelBuildConfig config;
    config.bvhBuilder = b;
    const BvhStackBuild build = buildBvhStack(sphere.tris, config);
    const AccelStats& s = build.stats;
    EXPECT_EQ(s.name, "bvh-stack");
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);  // a binary tree
    EXPECT_GE(s.references, sphere.tris.size());
    EXPECT_GT(s.depth, 1u);
    EXPECT_EQ(build.stackSize, s.depth);
    EXPECT_GT(s.sahCost, 0.0);
    EXPECT_GT(s.floatsPerTriangle, 0.0);
  }
  const BvhStackBuild single = buildBvhStack(testmesh::singleTriangle(), AccelBuildConfig{});
  EXPECT_EQ(single.stats.nodes, 1u);
  EXPECT_EQ(single.stats.leaves, 1u);
  EXPECT_EQ(single.stats.depth, 1u);
}

}  // namespace
}  // namespace passtrace
