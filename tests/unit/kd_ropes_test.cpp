// kd-ropes' ropes (accel/kd/kd_ropes.h), by brute force over the leaves of
// small trees: every rope of every leaf points to a node on the other side of
// that face whose box covers the face, no child of which still does; a face
// has no rope exactly when no leaf lies across it (the scene boundary). And
// the flattened texels hold the tree, ropes and boxes at the right offsets.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "accel/kd/kd_ropes.h"
#include "accel/kd/kd_ropes_structures.h"
#include "accel/kd/kd_ropes_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/registry.h"
#include "accel/kd/kd_structures.h"
#include "stream/texel_address.h"
#include "tests/kd_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;
using test::kd::build;
using test::kd::Builder;
using test::kd::kdMeshes;

// The plane coordinate of `box`'s face f, and of the face opposite it on the other side.
float facePlane(const Aabb& box, int f) { return (f & 1) ? box.max[f / 2] : box.min[f / 2]; }

// `other` lies across `leaf`'s face f: its opposite face is in the same plane.
bool across(const Aabb& leaf, int f, const Aabb& other) { return facePlane(other, f ^ 1) == facePlane(leaf, f); }

// `other` covers `leaf`'s face f along the two other axes.
bool covers(const Aabb& leaf, int f, const Aabb& other) {
  for (int b = 0; b < 3; ++b)
    if (b != f / 2 && (other.min[b] > leaf.min[b] || other.max[b] < leaf.max[b])) return false;
  return true;
}

// `other` overlaps `leaf`'s face f in an area (or a segment/point where the face is degenerate).
bool touchesFace(const Aabb& leaf, int f, const Aabb& other) {
  for (int b = 0; b < 3; ++b) {
    if (b == f / 2) continue;
    const bool flat = leaf.min[b] == leaf.max[b];
    if (flat ? (other.min[b] > leaf.min[b] || other.max[b] < leaf.min[b])
             : (other.min[b] >= leaf.max[b] || other.max[b] <= leaf.min[b]))
      return false;
  }
  return true;
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

class KdRopesTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdRopesTest, RopesReachTheSmallestNeighbourCoveringEachFace) {
  const auto& tris = GetParam().tris;
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    SCOPED_TRACE(b == Builder::Sah ? "sah" : "pbrt");
    // Small trees (at most 2^8 leaves): the brute force below is quadratic in the leaves.
    KdBuildConfig config = b == Builder::Sah ? KdBuildConfig{} : kPbrtKdConfig;
    config.maxDepth = 8;
    const KdTree tree = build(b, tris, &config);
    ASSERT_LE(tree.depth(), 9u);
    const std::vector<KdLeafRopes> ropes = buildKdRopes(tree);
    ASSERT_EQ(ropes.size(), tree.nodes.size());
    size_t checkedRopes = 0;
    for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
      const KdNode& leaf = tree.nodes[i];
      if (!leaf.isLeaf()) {
        for (uint32_t r : ropes[i]) EXPECT_EQ(r, kNoHit);
        continue;
      }
      for (int f = 0; f < kKdFaces; ++f) {
        SCOPED_TRACE("leaf " + std::to_string(i) + " face " + std::to_string(f));
        bool neighbour = false;  // brute force: some leaf lies across the face and touches it
        for (uint32_t j = 0; j < tree.nodes.size(); ++j) {
          const KdNode& other = tree.nodes[j];
          if (j != i && other.isLeaf() && across(leaf.box, f, other.box) && touchesFace(leaf.box, f, other.box))
            neighbour = true;
        }
        const uint32_t r = ropes[i][f];
        if (r == kNoHit) {
          EXPECT_EQ(facePlane(leaf.box, f), facePlane(tree.bounds, f)) << "no rope, but not on the scene boundary";
          EXPECT_FALSE(neighbour) << "no rope, but a leaf lies across the face";
          continue;
        }
        ++checkedRopes;
        EXPECT_TRUE(neighbour) << "a rope, but no leaf lies across the face";
        ASSERT_LT(r, tree.nodes.size());
        EXPECT_NE(r, i);
        const KdNode& target = tree.nodes[r];
        EXPECT_TRUE(across(leaf.box, f, target.box)) << "the rope's node does not share the face's plane";
        EXPECT_TRUE(covers(leaf.box, f, target.box)) << "the rope's node does not cover the face";
        if (!target.isLeaf()) {
          for (uint32_t child : {r + 1, target.rightChild}) {
            const Aabb& c = tree.nodes[child].box;
            EXPECT_FALSE(across(leaf.box, f, c) && covers(leaf.box, f, c)) << "the rope could go down to " << child;
          }
        }
      }
    }
    if (tree.leafCount() > 1) EXPECT_GT(checkedRopes, 0u);
  }
}

TEST_P(KdRopesTest, TexelsHoldTheTreeRopesAndBoxes) {
  const auto& tris = GetParam().tris;
  const KdTree tree = build(Builder::Sah, tris);
  const std::vector<KdLeafRopes> ropes = buildKdRopes(tree);
  const KdRopesTexels texels = flattenKdRopes(tree, ropes, tris.size());
  size_t expected = 0, entries = 0;
  for (const KdNode& n : tree.nodes) {
    expected += n.isLeaf() ? kKdRopesLeafTexels : kKdRopesInternalTexels;
    if (n.isLeaf() && n.refCount > 0) entries += n.refCount + 1;
  }
  ASSERT_EQ(texels.nodes.size(), expected);
  EXPECT_EQ(texels.listEntries, entries);
  if (!tris.empty())
    EXPECT_DOUBLE_EQ(texels.floatsPerTriangle, (4.0 * expected + entries) / double(tris.size()));
  const auto rope = [&](uint32_t node) { return node == kNoHit ? -1.0f : packIndex(texels.offsets[node]); };
  for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode& n = tree.nodes[i];
    const uint32_t at = texels.offsets[i];
    if (!n.isLeaf()) {
      EXPECT_EQ(texels.offsets[i + 1], at + 1) << "the left child follows its parent";
      EXPECT_EQ(texels.nodes[at], glm::vec4(packIndex(texels.offsets[n.rightChild]), n.split, 0.0f,
                                            -(float(n.axis) + 2.0f)));
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(texels.nodes[at][a], rope(ropes[i][2 * a]));
      EXPECT_EQ(texels.nodes[at + 1][a], rope(ropes[i][2 * a + 1]));
    }
    EXPECT_EQ(n.refCount == 0, texels.nodes[at].w < 0.0f);
    EXPECT_EQ(glm::vec3(texels.nodes[at + 2]), n.box.min);
    EXPECT_EQ(glm::vec3(texels.nodes[at + 3]), n.box.max);
  }
}

// Rays on leaf faces, edges and corners: from every leaf's corners and face
// centres, along the axes and diagonals. Each must end well inside the step bound
// (no ping-pong between leaves) and find brute force's nearest t wherever
// kd-stack over the same tree does (rays starting on a surface, or along a
// zero-area triangle, may miss it in both: the tree's clipped lists, not the ropes).
TEST_P(KdRopesTest, RaysAlongLeafFacesAndEdgesEndAndAgreeWithBruteForce) {
  const auto& tris = GetParam().tris;
  if (tris.empty()) return;
  const AccelBuildConfig config;
  const auto ropes = makeKdRopesMirror(tris, config);
  const auto brute = makeBruteForceAccelerator(tris);
  const auto stack = makeCpuStructure("kd-stack", tris, config);
  const KdTree tree = buildKdTreeFor(tris, config);
  const AccelStats stats = ropes->stats();
  size_t entries = 0;
  for (const KdNode& n : tree.nodes)
    if (n.isLeaf() && n.refCount > 0) entries += n.refCount + 1;
  const uint64_t bound = kdRopesMaxSteps(stats.leaves, stats.depth, entries);
  const glm::vec3 dirs[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1},
                            {0, 0, -1}, {1, 1, 0}, {-1, 0, 1}, {1, 1, 1}, {-1, -1, -1}};
  size_t rays = 0, hits = 0, mismatches = 0, bothMiss = 0;
  uint32_t leavesUsed = 0;
  for (const KdNode& leaf : tree.nodes) {
    if (!leaf.isLeaf() || ++leavesUsed > 200) continue;  // a few hundred leaves are plenty
    const glm::vec3 c = 0.5f * (leaf.box.min + leaf.box.max);
    const glm::vec3 origins[] = {leaf.box.min, leaf.box.max, {c.x, c.y, leaf.box.min.z}, {leaf.box.max.x, c.y, c.z},
                                 {c.x, leaf.box.min.y, leaf.box.max.z}};
    for (const glm::vec3& o : origins)
      for (const glm::vec3& d : dirs) {
        const Ray ray{o, d, kInfinity};
        RayStats s;
        const Hit h = ropes->intersect(ray, false, &s);
        const Hit expected = brute->intersect(ray, false, nullptr);
        const Hit standard = stack->intersect(ray, false, nullptr);
        ++rays;
        hits += expected.found();
        EXPECT_LT(s.steps, bound) << "a ray on a leaf boundary hit the step bound";
        // Ties aside: rays along a shared edge hit two triangles a few ulps apart.
        const auto agree = [&](const Hit& x) {
          return x.found() == expected.found() &&
                 (!x.found() || std::fabs(x.t - expected.t) <= 1e-5f * std::max(1.0f, expected.t));
        };
        if (!agree(standard)) ++bothMiss;
        else if (!agree(h)) ++mismatches;
      }
  }
  EXPECT_LE(bothMiss, rays / 50 + 2) << "kd-stack itself disagrees with brute force too often";
  EXPECT_EQ(mismatches, 0u) << "of " << rays << " rays, " << hits << " hits";
}

std::vector<NamedMesh> ropeMeshes() {
  std::vector<NamedMesh> meshes = kdMeshes();
  for (NamedMesh& m : testmesh::standardMeshesAndCellBoundaries())
    if (m.name == "cellBoundaries") meshes.push_back(m);
  return meshes;
}

INSTANTIATE_TEST_SUITE_P(KdMeshes, KdRopesTest, ::testing::ValuesIn(ropeMeshes()), meshName);

}  // namespace
}  // namespace passtrace
