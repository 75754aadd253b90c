// Kay/Kajiya BVH, its escape-index sequence, the three CPU traversals and the
// accelerator factory. The sequential and recursive traversals of one tree
// must agree exactly (same hit, same step count); against brute force they
// may differ only in which of several triangles hit at the same t wins.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>

#include "accel/brute_force.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/cpu_accelerator.h"
#include "accel/registry.h"
#include "tests/registry_helpers.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "tests/bvh_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::expectValidBvh;
using testmesh::NamedMesh;

bool sameHit(const Hit& a, const Hit& b) { return a.id == b.id && a.t == b.t && a.u == b.u && a.v == b.v; }

bool tiedT(float a, float b) { return std::fabs(a - b) <= 1e-6f * std::max(std::fabs(a), std::fabs(b)); }

// Counts disagreements instead of failing per ray, so one bad mesh reports
// one line, not thousands.
struct Agreement {
  size_t rays = 0, hits = 0, seqVsRecursive = 0, stepMismatch = 0, foundMismatch = 0, tieMismatch = 0,
         bogusAnyHit = 0;
  uint64_t seqSteps = 0, bruteSteps = 0;
};

Agreement compareTraversals(const Bvh& bvh, std::span<const Triangle> tris, std::span<const Ray> rays) {
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  Agreement a;
  for (const Ray& ray : rays) {
    for (const bool anyHit : {false, true}) {
      ++a.rays;
      RayStats seqStats, recStats, bruteStats;
      const Hit s = traverseEscapeSequence(seq, ray, anyHit, &seqStats);
      const Hit r = traverseBvhRecursive(bvh, tris, ray, anyHit, &recStats);
      const Hit b = intersectBruteForce(tris, ray, anyHit, &bruteStats);
      a.seqSteps += seqStats.steps;
      a.bruteSteps += bruteStats.steps;
      if (!sameHit(s, r)) ++a.seqVsRecursive;
      if (seqStats.steps != recStats.steps || seqStats.triangleTests != recStats.triangleTests) ++a.stepMismatch;
      if (s.found() != b.found()) {
        ++a.foundMismatch;
        continue;
      }
      if (!s.found()) continue;
      ++a.hits;
      if (anyHit) {
        // Any hit will do, but it must be a real one before tMax.
        Hit check{ray.tMax};
        if (!intersectTriangle(ray.origin, ray.direction, tris[s.id], s.id, check) || !sameHit(check, s))
          ++a.bogusAnyHit;
      } else if (s.id != b.id && !tiedT(s.t, b.t)) {
        ++a.tieMismatch;
      }
    }
  }
  return a;
}

void expectAgreement(const Agreement& a, const std::string& what) {
  EXPECT_EQ(a.seqVsRecursive, 0u) << what;
  EXPECT_EQ(a.stepMismatch, 0u) << what;
  EXPECT_EQ(a.foundMismatch, 0u) << what;
  EXPECT_EQ(a.tieMismatch, 0u) << what;
  EXPECT_EQ(a.bogusAnyHit, 0u) << what;
}

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

// Makes an n-ary tree out of a binary one by merging random internal
// children into their parents (what a Goldsmith/Salmon tree looks like to
// flattening and traversal). Keeps child order and boxes.
Bvh collapseRandomly(const Bvh& in, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Bvh out;
  out.nodes.push_back(in.nodes[0]);
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0, 0}};  // (in node, out node)
  while (!stack.empty()) {
    const auto [src, dst] = stack.back();
    stack.pop_back();
    if (in.nodes[src].isLeaf()) continue;
    // Expand children: an internal child is replaced by its own children half the time.
    std::vector<uint32_t> kids;
    for (uint32_t c = 0; c < in.nodes[src].childCount; ++c) {
      const uint32_t child = in.children[in.nodes[src].firstChild + c];
      const BvhNode& cn = in.nodes[child];
      if (!cn.isLeaf() && (rng() & 1))
        for (uint32_t g = 0; g < cn.childCount; ++g) kids.push_back(in.children[cn.firstChild + g]);
      else
        kids.push_back(child);
    }
    out.nodes[dst].firstChild = static_cast<uint32_t>(out.children.size());
    out.nodes[dst].childCount = static_cast<uint32_t>(kids.size());
    for (const uint32_t kid : kids) {
      const auto index = static_cast<uint32_t>(out.nodes.size());
      out.nodes.push_back(in.nodes[kid]);
      out.nodes.back().firstChild = 0;
      out.nodes.back().childCount = in.nodes[kid].isLeaf() ? 0 : 1;  // fixed below, when expanded
      out.children.push_back(index);
      stack.emplace_back(kid, index);
    }
  }
  return out;
}

// --- per-mesh agreement --------------------------------------------------------

class BvhMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(BvhMeshTest, TreeIsValidBinaryAndCountsAddUp) {
  const auto& tris = GetParam().tris;
  const Bvh bvh = buildKayKajiya(tris);
  expectValidBvh(bvh, tris);
  EXPECT_EQ(bvh.leafCount(), tris.size());
  EXPECT_EQ(bvh.internalCount(), tris.size() - 1);
  for (const BvhNode& n : bvh.nodes) EXPECT_TRUE(n.isLeaf() || n.childCount == 2);
}

TEST_P(BvhMeshTest, SequentialRecursiveAndBruteForceAgree) {
  const auto& tris = GetParam().tris;
  const Bvh bvh = buildKayKajiya(tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 1000, 42);
  const Agreement a = compareTraversals(bvh, tris, rays);
  expectAgreement(a, GetParam().name);
  EXPECT_GT(a.hits, 0u) << "the ray set should hit something";
  std::cout << "[ stats    ] " << GetParam().name << ": " << tris.size() << " triangles, " << a.hits << " of " << a.rays
            << " queries hit, steps per query " << double(a.seqSteps) / double(a.rays) << " (brute force "
            << double(a.bruteSteps) / double(a.rays) << ")\n";
  // The escape sequence must do less work than brute force on real meshes.
  if (tris.size() >= 1000) {
    EXPECT_LT(a.seqSteps, a.bruteSteps / 4) << GetParam().name;
  }
}

TEST_P(BvhMeshTest, EscapeIndicesPointForwardToNodeStarts) {
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

TEST_P(BvhMeshTest, SwapProbabilityChangesChildOrderButNeverAHit) {
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

TEST_P(BvhMeshTest, NaryTreesFlattenAndTraverseAlike) {
  const auto& tris = GetParam().tris;
  const Bvh nary = collapseRandomly(buildKayKajiya(tris), 99);
  expectValidBvh(nary, tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 77);
  expectAgreement(compareTraversals(nary, tris, rays), GetParam().name + " (n-ary)");
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, BvhMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()), meshName);

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

TEST(KayKajiyaBvh, LargeSoupBuilds) {
  // Bunny-sized (the thesis's bunny has 69,451 triangles); time is printed, not asserted.
  const auto tris = testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.02f, 8);
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildKayKajiya(tris);
  const auto built = std::chrono::steady_clock::now();
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  const auto flat = std::chrono::steady_clock::now();
  using ms = std::chrono::duration<double, std::milli>;
  std::cout << "[ timing   ] K/K build of 100k triangles: " << ms(built - start).count() << " ms, flatten "
            << ms(flat - built).count() << " ms, depth " << bvh.depth() << "\n";
  EXPECT_EQ(bvh.leafCount(), tris.size());
  EXPECT_EQ(seq.texels.size(), 2 * (tris.size() - 1) + 3 * tris.size());
  EXPECT_LT(bvh.depth(), 64u);
}

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

TEST(BvhTraversal, HitsAtOrBeyondTMaxAreIgnored) {
  const auto tris = testmesh::flatGrid(4, 4, 2, 0.0f);
  const Bvh bvh = buildKayKajiya(tris);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  Ray ray{glm::vec3(0.3f, 0.6f, 2.0f), glm::vec3(0, 0, -1)};
  const Hit open = traverseEscapeSequence(seq, ray, false);
  ASSERT_TRUE(open.found());
  EXPECT_EQ(open.t, 2.0f);
  ray.tMax = 2.0f;  // exactly at the hit: excluded
  for (const bool anyHit : {false, true}) {
    EXPECT_FALSE(traverseEscapeSequence(seq, ray, anyHit).found());
    EXPECT_FALSE(traverseBvhRecursive(bvh, tris, ray, anyHit).found());
    EXPECT_FALSE(intersectBruteForce(tris, ray, anyHit).found());
  }
  ray.tMax = std::nextafter(2.0f, 3.0f);
  EXPECT_TRUE(traverseEscapeSequence(seq, ray, true).found());
}

TEST(BvhTraversal, RaysLyingInABoxFacePlane) {
  // A direction component of exactly zero: the slab test treats the ray as
  // inside a slab it lies in, on the min face and on the max face alike, so
  // the BVH finds the edge hits brute force finds (x = 0 and x = 1 are the
  // grid's min and max faces).
  const auto tris = testmesh::flatGrid(4, 4, 2, 0.0f);  // [0,1]^2 at z = 0, grid lines every 0.25
  const Bvh bvh = buildKayKajiya(tris);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  for (const float x : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
    for (const float dx : {0.0f, -0.0f}) {
      const Ray ray{glm::vec3(x, 0.3f, 1.0f), glm::vec3(dx, 0.0f, -1.0f)};
      RayStats s, r;
      const Hit hs = traverseEscapeSequence(seq, ray, false, &s);
      const Hit hr = traverseBvhRecursive(bvh, tris, ray, false, &r);
      EXPECT_TRUE(sameHit(hs, hr)) << x;
      EXPECT_EQ(s.steps, r.steps) << x;
      const Hit hb = intersectBruteForce(tris, ray, false);
      EXPECT_TRUE(hb.found()) << x;
      EXPECT_TRUE(hs.found()) << x;
      EXPECT_EQ(hs.t, hb.t) << x;
    }
  }
}

TEST(BvhTraversal, AnyHitStopsEarlyAndStatsAccumulate) {
  // Ten parallel planes stacked along z; a ray through all of them.
  std::vector<Triangle> tris;
  for (int k = 0; k < 10; ++k) {
    const auto plane = testmesh::flatGrid(2, 2, 2, float(k));
    tris.insert(tris.end(), plane.begin(), plane.end());
  }
  const Bvh bvh = buildKayKajiya(tris);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  const Ray ray{glm::vec3(0.3f, 0.6f, -1.0f), glm::vec3(0, 0, 1)};
  RayStats closest, any;
  const Hit c = traverseEscapeSequence(seq, ray, false, &closest);
  const Hit a = traverseEscapeSequence(seq, ray, true, &any);
  EXPECT_EQ(c.t, 1.0f);  // the z = 0 plane
  EXPECT_TRUE(a.found());
  EXPECT_LE(any.steps, closest.steps);
  RayStats twice;
  traverseEscapeSequence(seq, ray, false, &twice);
  traverseEscapeSequence(seq, ray, false, &twice);
  EXPECT_EQ(twice.steps, 2 * closest.steps);
}

TEST(BruteForce, TiesGoToTheLowestSceneIndexAndEveryTriangleIsTested) {
  const auto one = testmesh::singleTriangle();
  const std::vector<Triangle> tris = {one[0], one[0], one[0]};  // three identical triangles
  const Ray ray{glm::vec3(-0.5f, -0.5f, 1.0f), glm::vec3(0, 0, -1)};
  RayStats stats;
  EXPECT_EQ(intersectBruteForce(tris, ray, false, &stats).id, 0u);
  EXPECT_EQ(stats.steps, 3u);
  EXPECT_EQ(stats.triangleTests, 3u);
  RayStats anyStats;
  EXPECT_EQ(intersectBruteForce(tris, ray, true, &anyStats).id, 0u);
  EXPECT_EQ(anyStats.steps, 1u);
}

// --- the accelerator interface -------------------------------------------------

TEST(CpuAccelerator, KayKajiyaSequentialAndRecursiveMatchBruteForce) {
  const auto tris = testmesh::uvSphere(16, 24);
  const auto seq = testing_registry::cpuStructure(0, tris, {});
  const auto rec = testing_registry::cpuStructure(5, tris, {});
  const auto brute = makeBruteForceAccelerator(tris);
  EXPECT_EQ(seq->name(), "kk-bvh");
  EXPECT_EQ(rec->name(), "kk-bvh-recursive");
  EXPECT_EQ(brute->name(), "brute-force");
  for (const Ray& ray : testmesh::rayMix(testmesh::boundsOf(tris), 200, 3)) {
    RayStats s, r;
    const Hit hs = seq->intersect(ray, false, &s);
    const Hit hr = rec->intersect(ray, false, &r);
    const Hit hb = brute->intersect(ray, false, nullptr);
    EXPECT_TRUE(sameHit(hs, hr));
    EXPECT_EQ(s.steps, r.steps);
    ASSERT_EQ(hs.found(), hb.found());
    if (hs.id != hb.id) {
      EXPECT_TRUE(tiedT(hs.t, hb.t));
    }
  }
}

TEST(CpuAccelerator, StatsDescribeTheTree) {
  const auto tris = testmesh::triangleSoup(32, Aabb{glm::vec3(0), glm::vec3(1)}, 0.2f, 1);
  for (const int number : {0, 5}) {
    const AccelStats s = testing_registry::cpuStructure(number, tris, {})->stats();
    EXPECT_EQ(s.name, testing_registry::cpuName(number));
    EXPECT_EQ(s.nodes, 63u);
    EXPECT_EQ(s.leaves, 32u);
    EXPECT_EQ(s.references, 32u);
    EXPECT_DOUBLE_EQ(s.floatsPerTriangle, 7.75);
    EXPECT_GE(s.depth, 6u);
    EXPECT_GE(s.buildMs, 0.0);
  }
  const AccelStats b = makeBruteForceAccelerator(tris)->stats();
  EXPECT_EQ(b.references, 32u);
  EXPECT_EQ(b.nodes, 0u);
}

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
