// The BVH traversals over one tree: the escape-index sequence and the
// recursive descent must agree exactly (same hit, same step count), on binary
// and n-ary trees; against brute force they may differ only in which of
// several triangles hit at the same t wins. Also the K/K accelerators.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/cpu_accelerator.h"
#include "tests/bvh_checks.h"
#include "tests/hit_checks.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::expectValidBvh;
using test::sameHit;
using test::tiedT;
using testmesh::NamedMesh;

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

TEST_P(BvhMeshTest, SequentialRecursiveAndBruteForceAgree) {
  const auto& tris = GetParam().tris;
  const Bvh bvh = buildKayKajiya(tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 1000, 42);
  const Agreement a = compareTraversals(bvh, tris, rays);
  expectAgreement(a, GetParam().name);
  EXPECT_GT(a.hits, 0u) << "the ray set should hit something";
  // The escape sequence must do less work than brute force on real meshes.
  if (tris.size() >= 1000) {
    EXPECT_LT(a.seqSteps, a.bruteSteps / 4) << GetParam().name;
  }
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

// --- traversal details --------------------------------------------------------

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

}  // namespace
}  // namespace passtrace
