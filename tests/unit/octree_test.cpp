// The octree (CPU structure octree): every node reached once, every
// triangle in a leaf, children inside their parents, the depth limit, and
// floats per triangle.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "accel/cpu_accelerator.h"
#include "accel/octree/octree.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;

class OctreeMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(OctreeMeshTest, OctreeIsValid) {
  const auto& tris = GetParam().tris;
  const Octree tree = buildOctree(tris);
  ASSERT_FALSE(tree.nodes.empty());
  const Aabb bounds = testmesh::boundsOf(tris);
  EXPECT_TRUE(glm::all(glm::lessThanEqual(tree.nodes[0].box.min, bounds.min)) &&
              glm::all(glm::greaterThanEqual(tree.nodes[0].box.max, bounds.max)));
  std::vector<int> seen(tree.nodes.size(), 0), triSeen(tris.size(), 0);
  size_t refs = 0;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const uint32_t n = stack.back();
    stack.pop_back();
    ASSERT_EQ(seen[n]++, 0);
    const OctreeNode& node = tree.nodes[n];
    if (node.isLeaf()) {
      refs += node.refCount;
      for (uint32_t r = node.firstRef; r < node.firstRef + node.refCount; ++r) ++triSeen[tree.references[r]];
      continue;
    }
    EXPECT_LE(node.childCount, 8u);
    EXPECT_EQ(node.refCount, 0u);
    for (uint32_t c = 0; c < node.childCount; ++c) {
      const Aabb& cb = tree.nodes[node.firstChild + c].box;
      EXPECT_TRUE(glm::all(glm::lessThanEqual(node.box.min, cb.min)) &&
                  glm::all(glm::greaterThanEqual(node.box.max, cb.max)));
      stack.push_back(node.firstChild + c);
    }
  }
  for (size_t n = 0; n < seen.size(); ++n) EXPECT_EQ(seen[n], 1) << "node " << n;
  for (size_t t = 0; t < tris.size(); ++t) EXPECT_GE(triSeen[t], 1) << "triangle " << t << " in no leaf";
  EXPECT_EQ(refs, tree.references.size());
  const uint32_t autoDepth = uint32_t(std::ceil(std::log(double(tris.size())) / std::log(8.0) - 1e-9)) + 3;
  EXPECT_LE(tree.depth, std::clamp(autoDepth, 1u, 16u) + 1);
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, OctreeMeshTest, ::testing::ValuesIn(testmesh::standardMeshesAndCellBoundaries()), meshName);

// --- octree ------------------------------------------------------------------------

TEST(Octree, FloatsPerTriangleAndLimits) {
  const auto tris = testmesh::triangleSoup(4000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.05f, 8);
  const Octree tree = buildOctree(tris, {.maxDepth = 3, .maxLeafTriangles = 4});
  EXPECT_LE(tree.depth, 4u);
  EXPECT_DOUBLE_EQ(tree.floatsPerTriangle(tris.size()),
                   (8.0 * double(tree.nodes.size()) + double(tree.references.size())) / 4000.0);
  const AccelStats s = testing_registry::cpuStructure(7, tris)->stats();
  const Octree byDefault = buildOctree(tris);
  EXPECT_EQ(s.name, "octree-descent");
  EXPECT_EQ(s.nodes, byDefault.nodes.size());
  EXPECT_EQ(s.leaves, byDefault.leafCount());
  EXPECT_EQ(s.references, byDefault.references.size());
  EXPECT_EQ(s.depth, byDefault.depth);
  EXPECT_DOUBLE_EQ(s.floatsPerTriangle, byDefault.floatsPerTriangle(tris.size()));
  // Coincident triangles: a zero-size cube is one leaf.
  const Octree point = buildOctree(testmesh::pointMesh(500));
  EXPECT_EQ(point.nodes.size(), 1u);
  EXPECT_EQ(point.depth, 1u);
  EXPECT_TRUE(buildOctree({}).nodes.empty());
}

}  // namespace
}  // namespace passtrace
