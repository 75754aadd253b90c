// The escape-index sequence a BVH flattens to: every box's escape index
// points forward to a node start and its children tile the texels up to it,
// the exact texel layout of a hand-built tree, and index packing.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;

// Escape index of every box (texel index -> escape), walking node boundaries.
std::vector<std::pair<uint32_t, uint32_t>> boxEscapes(const EscapeSequence& seq, std::set<uint32_t>* starts) {
  std::vector<std::pair<uint32_t, uint32_t>> escapes;
  uint32_t i = 0;
  while (i < seq.texels.size()) {
    if (starts) starts->insert(i);
    if (seq.texels[i].w >= 0.0f) {
      escapes.emplace_back(i, unpackIndex(seq.texels[i].w));
      i += 2;
    } else {
      i += 3;
    }
  }
  EXPECT_EQ(i, seq.texels.size()) << "sequence ends inside a node";
  return escapes;
}

class EscapeSequenceMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(EscapeSequenceMeshTest, EscapeIndicesPointForwardToNodeStarts) {
  const auto& tris = GetParam().tris;
  const EscapeSequence seq = flattenEscapeSequence(buildKayKajiya(tris), tris);
  std::set<uint32_t> starts;
  const auto escapes = boxEscapes(seq, &starts);
  starts.insert(static_cast<uint32_t>(seq.texels.size()));
  for (const auto& [at, escape] : escapes) {
    EXPECT_GT(escape, at + 2) << "escape of box " << at << " must skip at least one child";
    EXPECT_LE(escape, seq.texels.size());
    EXPECT_TRUE(starts.count(escape)) << "escape of box " << at << " lands inside a node";
  }
  // Each box's children tile [box + 2, escape) exactly, so its last child ends
  // where the box escapes to; down the right edge (root, its last child, that
  // one's last child, ...) every box escapes to the end of the sequence.
  auto nodeEnd = [&](uint32_t i) { return seq.texels[i].w >= 0.0f ? unpackIndex(seq.texels[i].w) : i + 3; };
  for (const auto& [at, escape] : escapes) {
    uint32_t child = at + 2, last = child;
    while (child < escape) {
      last = child;
      child = nodeEnd(child);
    }
    EXPECT_EQ(child, escape) << "children of box " << at << " overrun its escape";
    EXPECT_EQ(nodeEnd(last), escape);
  }
  if (!escapes.empty()) {
    ASSERT_EQ(escapes.front().first, 0u) << "the root is a box";
    uint32_t box = 0, chain = 0;
    for (;;) {
      EXPECT_EQ(unpackIndex(seq.texels[box].w), seq.texels.size()) << "right-edge box " << box;
      ++chain;
      uint32_t child = box + 2, last = child;
      while (child < seq.texels.size()) {
        last = child;
        child = nodeEnd(child);
      }
      if (seq.texels[last].w < 0.0f) break;  // the rightmost leaf
      box = last;
    }
    EXPECT_GE(chain, 1u);
  }
  EXPECT_EQ(seq.boxCount, escapes.size());
  EXPECT_EQ(seq.texels.size(), 2 * size_t{seq.boxCount} + 3 * size_t{seq.triangleCount});
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, EscapeSequenceMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()), meshName);

// --- escape sequence layout and traversal details ------------------------------

TEST(EscapeSequenceBvh, ExactTexelLayoutOfAHandBuiltTree) {
  // root(box) -> [leaf t2, inner(box) -> [leaf t0, leaf t1], leaf t3]: a
  // ternary root, as a Goldsmith/Salmon tree may have.
  const std::vector<Triangle> tris = {
      {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)},
      {glm::vec3(2, 0, 0), glm::vec3(3, 0, 0), glm::vec3(2, 1, 0)},
      {glm::vec3(4, 0, 0), glm::vec3(5, 0, 0), glm::vec3(4, 1, 0)},
      {glm::vec3(6, 0, 0), glm::vec3(7, 0, 0), glm::vec3(6, 1, 0)},
  };
  Bvh bvh;
  auto leaf = [&](uint32_t t) { return BvhNode{tris[t].bounds(), t}; };
  Aabb all = testmesh::boundsOf(tris), inner;
  inner.extend(tris[0].bounds());
  inner.extend(tris[1].bounds());
  bvh.nodes = {BvhNode{all, kNoHit, 0, 3}, leaf(2), BvhNode{inner, kNoHit, 3, 2}, leaf(3), leaf(0), leaf(1)};
  bvh.children = {1, 2, 3, 4, 5};
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  // texels: root 0-1, t2 2-4, inner 5-6, t0 7-9, t1 10-12, t3 13-15.
  ASSERT_EQ(seq.texels.size(), 16u);
  EXPECT_EQ(seq.boxCount, 2u);
  EXPECT_EQ(seq.triangleCount, 4u);
  EXPECT_FLOAT_EQ(seq.floatsPerTriangle(), 4.0f);
  EXPECT_EQ(seq.texels[0], glm::vec4(all.min, packIndex(16)));
  EXPECT_EQ(seq.texels[1], glm::vec4(all.max, 0.0f));
  EXPECT_EQ(seq.texels[2], glm::vec4(tris[2].v0, -1.0f));
  EXPECT_EQ(seq.texels[3], glm::vec4(tris[2].v1, packIndex(2)));
  EXPECT_EQ(seq.texels[4], glm::vec4(tris[2].v2, 0.0f));
  EXPECT_EQ(seq.texels[5], glm::vec4(inner.min, packIndex(13)));
  EXPECT_EQ(seq.texels[6], glm::vec4(inner.max, 0.0f));
  EXPECT_EQ(unpackIndex(seq.texels[8].w), 0u);
  EXPECT_EQ(unpackIndex(seq.texels[11].w), 1u);
  EXPECT_EQ(seq.texels[13], glm::vec4(tris[3].v0, -1.0f));
  EXPECT_EQ(unpackIndex(seq.texels[14].w), 3u);

  // A ray along -z through x = 6.25 misses the inner box: root, t2, inner, t3.
  RayStats stats;
  const Ray ray{glm::vec3(6.25f, 0.25f, 1.0f), glm::vec3(0, 0, -1)};
  EXPECT_EQ(traverseEscapeSequence(seq, ray, false, &stats).id, 3u);
  EXPECT_EQ(stats.steps, 4u);
  EXPECT_EQ(stats.triangleTests, 2u);
  RayStats recursive;
  EXPECT_EQ(traverseBvhRecursive(bvh, tris, ray, false, &recursive).id, 3u);
  EXPECT_EQ(recursive.steps, 4u);
}

TEST(EscapeSequenceBvh, PackedIndicesAreNormalPositiveAndExact) {
  for (const uint32_t i : {0u, 1u, 2u, 16777216u, 16777217u, 0x7EFFFFFFu}) {
    const float f = packIndex(i);
    EXPECT_TRUE(std::isnormal(f)) << i;
    EXPECT_GT(f, 0.0f);
    EXPECT_EQ(unpackIndex(f), i);
  }
}

TEST(EscapeSequenceBvh, RejectsLeavesNamingMissingTriangles) {
  const auto tris = testmesh::singleTriangle();
  Bvh bvh;
  bvh.nodes = {BvhNode{tris[0].bounds(), 5}};
  EXPECT_THROW(flattenEscapeSequence(bvh, tris), std::invalid_argument);
}

}  // namespace
}  // namespace passtrace
