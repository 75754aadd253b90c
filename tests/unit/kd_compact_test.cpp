// kd-compact's 8-byte nodes (accel/kd/kd_compact_node.h): two per texel, and
// each decodes to the restart layout's texel of the same node (but the parent,
// which the stack traversal does not read), with lists identical to restart's.

#include <gtest/gtest.h>

#include <string>

#include "accel/kd/kd_compact_node.h"
#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_tree.h"
#include "tests/kd_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;
using test::kd::build;
using test::kd::Builder;
using test::kd::kdMeshes;

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

class KdCompactTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdCompactTest, EightByteNodesDecodeToTheRestartLayout) {
  const auto& tris = GetParam().tris;
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, tris);
    const KdTexels restart = flattenKdRestart(tree, tris.size());
    const KdTexels compact = flattenKdCompact(tree, tris.size());
    ASSERT_EQ(compact.nodes.size(), (tree.nodes.size() + 1) / 2) << "two nodes per 16-byte texel";
    EXPECT_EQ(compact.lists, restart.lists);
    EXPECT_EQ(compact.listEntries, restart.listEntries);
    if (!tris.empty())
      EXPECT_DOUBLE_EQ(compact.floatsPerTriangle,
                       (2.0 * tree.nodes.size() + restart.listEntries) / double(tris.size()));
    for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
      glm::vec4 expected = restart.nodes[i];
      expected.z = -1.0f;
      if (tree.nodes[i].isLeaf()) expected.x = expected.y = 0.0f;
      EXPECT_EQ(kdCompactNodeTexel(compact.nodes, i), expected) << "node " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(KdMeshes, KdCompactTest, ::testing::ValuesIn(kdMeshes()), meshName);

}  // namespace
}  // namespace passtrace
