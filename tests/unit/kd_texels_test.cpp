// Kd-tree texels: the kd-restart (one texel per node) and kd-backtrack
// (three, with the node's box) layouts the GPU kernels read, against the tree.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/reference_lists.h"
#include "stream/texel_address.h"
#include "tests/kd_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;
using test::kd::build;
using test::kd::Builder;
using test::kd::expectMinElements;
using test::kd::expectValidKdTree;
using test::kd::kdMeshes;

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

class KdTexelsMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdTexelsMeshTest, FlattenedLayoutsMatchTheTree) {
  const auto& tris = GetParam().tris;
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, tris);
    const KdTexels restart = flattenKdRestart(tree, tris.size());
    const KdTexels backtrack = flattenKdBacktrack(tree, tris.size());
    EXPECT_EQ(restart.nodeStride, 1u);
    EXPECT_EQ(backtrack.nodeStride, 3u);
    ASSERT_EQ(restart.nodes.size(), tree.nodes.size());
    ASSERT_EQ(backtrack.nodes.size(), 3 * tree.nodes.size());
    EXPECT_EQ(restart.lists, backtrack.lists);
    EXPECT_EQ(restart.listEntries, backtrack.listEntries);

    size_t entries = 0;
    for (const KdNode& n : tree.nodes)
      if (n.isLeaf() && n.refCount > 0) entries += n.refCount + 1;
    EXPECT_EQ(restart.listEntries, entries);
    EXPECT_EQ(restart.lists.size(), (entries + 3) / 4);
    const double n = static_cast<double>(tris.size());
    EXPECT_DOUBLE_EQ(restart.floatsPerTriangle, (4.0 * tree.nodes.size() + entries) / n);
    EXPECT_DOUBLE_EQ(backtrack.floatsPerTriangle, (12.0 * tree.nodes.size() + entries) / n);
    EXPECT_DOUBLE_EQ(kdFloatsPerTriangle(tree, tris.size(), 1), restart.floatsPerTriangle);
    EXPECT_DOUBLE_EQ(kdFloatsPerTriangle(tree, tris.size(), 3), backtrack.floatsPerTriangle);

    auto listEntry = [&](size_t j) { return restart.lists[j / 4][int(j % 4)]; };
    for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
      const KdNode& node = tree.nodes[i];
      const glm::vec4 t0 = restart.nodes[i];
      EXPECT_EQ(backtrack.nodes[3 * i], t0);
      EXPECT_EQ(backtrack.nodes[3 * i + 1], glm::vec4(node.box.min, 0.0f));
      EXPECT_EQ(backtrack.nodes[3 * i + 2], glm::vec4(node.box.max, 0.0f));
      if (i == 0)
        EXPECT_EQ(t0.z, -1.0f);
      else
        EXPECT_EQ(unpackIndex(t0.z), node.parent);
      if (!node.isLeaf()) {
        EXPECT_EQ(unpackIndex(t0.x), node.rightChild);
        EXPECT_EQ(t0.y, node.split);
        EXPECT_EQ(t0.w, -(float(node.axis) + 2.0f));
        EXPECT_TRUE(t0.w == -2.0f || t0.w == -3.0f || t0.w == -4.0f);
        continue;
      }
      EXPECT_EQ(t0.x, 0.0f);
      EXPECT_EQ(t0.y, 0.0f);
      if (node.refCount == 0) {
        EXPECT_EQ(t0.w, -1.0f);
        continue;
      }
      ASSERT_GT(t0.w, 0.0f);
      const uint32_t start = unpackIndex(t0.w);
      ASSERT_LT(start + node.refCount, restart.listEntries);
      for (uint32_t r = 0; r < node.refCount; ++r)
        EXPECT_EQ(unpackIndex(listEntry(start + r)), tree.references[node.firstRef + r]);
      EXPECT_EQ(listEntry(start + node.refCount), kListEnd);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, KdTexelsMeshTest, ::testing::ValuesIn(kdMeshes()), meshName);

TEST(KdTree, SingleTriangleIsALeafRootWithExactTexels) {
  const auto tris = testmesh::singleTriangle();
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, tris);
    ASSERT_EQ(tree.nodes.size(), 1u);
    EXPECT_TRUE(tree.nodes[0].isLeaf());
    EXPECT_EQ(tree.references, std::vector<uint32_t>{0});
    const KdTexels tex = flattenKdRestart(tree, 1);
    ASSERT_EQ(tex.nodes.size(), 1u);
    EXPECT_EQ(tex.nodes[0], glm::vec4(0.0f, 0.0f, -1.0f, packIndex(0)));
    ASSERT_EQ(tex.lists.size(), 1u);
    EXPECT_EQ(tex.lists[0], glm::vec4(packIndex(0), kListEnd, kListEnd, kListEnd));
    EXPECT_EQ(tex.listEntries, 2u);
    EXPECT_DOUBLE_EQ(tex.floatsPerTriangle, 6.0);  // 4 node floats + 2 list entries
    const Ray ray{glm::vec3(-0.5f, -0.5f, 2.0f), glm::vec3(0, 0, -1)};
    RayStats stats;
    const Hit hit = traverseKdTree(tree, tris, ray, false, &stats);
    EXPECT_EQ(hit.id, 0u);
    EXPECT_FLOAT_EQ(hit.t, 2.0f);
    EXPECT_EQ(stats.steps, 1u);
    EXPECT_EQ(stats.triangleTests, 1u);
  }
}

TEST(KdTree, InternalTexelsEncodeAxisSplitChildAndParent) {
  // Two clusters far apart along y: the root splits on y.
  std::vector<Triangle> tris = testmesh::triangleSoup(40, Aabb{glm::vec3(0), glm::vec3(1)}, 0.1f, 4);
  const auto far = testmesh::triangleSoup(40, Aabb{glm::vec3(0, 10, 0), glm::vec3(1, 11, 1)}, 0.1f, 5);
  tris.insert(tris.end(), far.begin(), far.end());
  const KdTree tree = buildKdTree(tris);
  ASSERT_FALSE(tree.nodes[0].isLeaf());
  EXPECT_EQ(tree.nodes[0].axis, 1u);
  EXPECT_GE(tree.nodes[0].split, 1.0f - 0.05f);
  EXPECT_LE(tree.nodes[0].split, 10.0f + 0.05f);
  const KdTexels tex = flattenKdBacktrack(tree, tris.size());
  EXPECT_EQ(tex.nodes[0], glm::vec4(packIndex(tree.nodes[0].rightChild), tree.nodes[0].split, -1.0f, -3.0f));
  const uint32_t right = tree.nodes[0].rightChild;
  EXPECT_EQ(tex.nodes[3 * right].z, packIndex(0));
  EXPECT_EQ(tex.nodes[3 * 1].z, packIndex(0));
}

}  // namespace
}  // namespace passtrace
