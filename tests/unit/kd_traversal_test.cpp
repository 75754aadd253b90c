// Kd-tree stack traversal (CPU structures kd-tree and kd-pbrt) against brute
// force; the rays include the ones kd-trees get wrong most easily: parallel
// to split planes, and starting exactly on them. Also trees deeper than the
// builders make.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/kd/kd_structures.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "tests/kd_checks.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;
using test::kd::build;
using test::kd::Builder;
using test::kd::expectMinElements;
using test::kd::expectValidKdTree;
using test::kd::kdMeshes;

using test::kd::Agreement;
using test::kd::compare;
using test::kd::expectAgreement;

// Rays built from the tree's own split planes: starting exactly on a plane
// (random direction; direction in the plane; direction along the axis) and
// parallel to a plane, just off it on either side. Half have finite tMax.
std::vector<Ray> splitPlaneRays(const KdTree& tree, const Aabb& bounds, size_t count, uint64_t seed) {
  std::vector<Ray> rays;
  std::vector<const KdNode*> internal;
  for (const KdNode& n : tree.nodes)
    if (!n.isLeaf()) internal.push_back(&n);
  if (internal.empty()) return rays;
  std::mt19937_64 rng(seed);
  auto unit = [&] { return static_cast<float>(static_cast<double>(rng() >> 11) * 0x1.0p-53); };
  const glm::vec3 lo = bounds.min - 0.1f * bounds.extent() - glm::vec3(1e-3f);
  const glm::vec3 hi = bounds.max + 0.1f * bounds.extent() + glm::vec3(1e-3f);
  const float diagonal = glm::length(hi - lo);
  for (size_t r = 0; r < count; ++r) {
    const KdNode& n = *internal[rng() % internal.size()];
    const int axis = static_cast<int>(n.axis);
    Ray ray;
    for (int k = 0; k < 3; ++k) ray.origin[k] = lo[k] + (hi[k] - lo[k]) * unit();
    ray.origin[axis] = n.split;
    glm::vec3 d{unit() * 2 - 1, unit() * 2 - 1, unit() * 2 - 1};
    if (glm::dot(d, d) < 1e-4f) d = glm::vec3(0.3f, -0.5f, 0.8f);
    d = glm::normalize(d);
    switch (r % 5) {
      case 0:  // on the plane, leaving it
        break;
      case 1:  // in the plane
        d[axis] = 0.0f;
        break;
      case 2:  // on the plane, along one of the other axes (two zero components)
        d = glm::vec3(0.0f);
        d[(axis + 1 + rng() % 2) % 3] = (rng() & 1) ? 1.0f : -1.0f;
        break;
      case 3:  // parallel, a few ulps off the plane
        d[axis] = 0.0f;
        ray.origin[axis] = std::nextafter(n.split, (rng() & 1) ? kInfinity : -kInfinity);
        break;
      case 4:  // on the plane, straight along the split axis
        d = glm::vec3(0.0f);
        d[axis] = (rng() & 1) ? 1.0f : -1.0f;
        break;
    }
    if (glm::dot(d, d) == 0.0f) d[(axis + 1) % 3] = 1.0f;
    ray.direction = d;
    if (r % 2) ray.tMax = unit() * diagonal;
    rays.push_back(ray);
  }
  return rays;
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

// --- per mesh ----------------------------------------------------------------------

class KdMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdMeshTest, AcceleratorsAgreeWithBruteForce) {
  const auto& tris = GetParam().tris;
  const Aabb bounds = testmesh::boundsOf(tris);
  const std::vector<Ray> mix = testmesh::rayMix(bounds, 1000, 91);
  for (const int number : {2, 3}) {
    const auto accel = testing_registry::cpuStructure(number, tris);
    const KdTree tree = number == 2 ? buildKdTree(tris) : buildKdTreePbrt(tris);
    const std::vector<Ray> planes = splitPlaneRays(tree, bounds, 3000, 17 + number);
    const Agreement a = compare(*accel, tris, mix);
    const Agreement p = compare(*accel, tris, planes);
    const std::string what = GetParam().name + " accelerator " + std::to_string(number);
    expectAgreement(a, what + " (ray mix)");
    expectAgreement(p, what + " (split-plane rays)");
    EXPECT_GT(a.hits, 0u) << what;
    const AccelStats s = accel->stats();
    if (tris.size() >= 1000 && GetParam().name != "degenerate") {
      EXPECT_LT(a.kdTests, a.bruteTests / 4) << what;
    }
  }
}

TEST_P(KdMeshTest, TraversalMatchesTheAcceleratorAndCountsWork) {
  const auto& tris = GetParam().tris;
  const KdTree tree = buildKdTree(tris, kdConfigFor(AccelBuildConfig{}));
  const auto accel = testing_registry::cpuStructure(2, tris);
  for (const Ray& ray : testmesh::rayMix(testmesh::boundsOf(tris), 40, 5)) {
    RayStats direct, viaAccel;
    const Hit h1 = traverseKdTree(tree, tris, ray, false, &direct);
    const Hit h2 = accel->intersect(ray, false, &viaAccel);
    EXPECT_EQ(h1.id, h2.id);
    EXPECT_EQ(h1.t, h2.t);
    EXPECT_EQ(direct.steps, viaAccel.steps);
    EXPECT_EQ(direct.triangleTests, viaAccel.triangleTests);
    EXPECT_LE(direct.steps, tree.nodes.size());
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, KdMeshTest, ::testing::ValuesIn(kdMeshes()), meshName);

TEST(KdTree, ParallelRayOnASplitPlaneSeesBothSides) {
  // Two quads meeting at x = 0 and a ray along y lying in x = 0: with the
  // split at x = 0 it must look on both sides and find the nearer one.
  std::vector<Triangle> tris;
  for (int k = 0; k < 6; ++k) {  // walls at y = 1 + k on the left, y = 1.5 + k on the right
    const float yl = 1.0f + float(k), yr = 1.5f + float(k);
    tris.push_back({glm::vec3(-1, yl, -1), glm::vec3(0, yl, -1), glm::vec3(0, yl, 1)});
    tris.push_back({glm::vec3(-1, yl, -1), glm::vec3(0, yl, 1), glm::vec3(-1, yl, 1)});
    tris.push_back({glm::vec3(0, yr, -1), glm::vec3(1, yr, -1), glm::vec3(1, yr, 1)});
    tris.push_back({glm::vec3(0, yr, -1), glm::vec3(1, yr, 1), glm::vec3(0, yr, 1)});
  }
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, tris);
    expectValidKdTree(tree, tris, "walls");
    for (const float z : {-0.5f, 0.0f, 0.5f}) {
      const Ray ray{glm::vec3(0, 0, z), glm::vec3(0, 1, 0)};
      const Hit kd = traverseKdTree(tree, tris, ray, false), brute = intersectBruteForce(tris, ray, false);
      ASSERT_EQ(kd.found(), brute.found());
      EXPECT_FLOAT_EQ(kd.t, brute.t);
      EXPECT_FLOAT_EQ(kd.t, 1.0f);
    }
  }
}

TEST(KdTree, TraversalHandlesTreesDeeperThanTheBuildersMake) {
  // A hand-made chain of 100 x splits at 1 - (i + 1) / 128 (left child: the
  // next split; right child: a leaf holding one wall across the ray), deeper
  // than kKdDepthLimit: the traversal stack must spill, not overflow.
  constexpr uint32_t kChain = 100;
  static_assert(kChain > kKdDepthLimit);
  KdTree tree;
  std::vector<Triangle> tris;
  tree.nodes.resize(2 * kChain + 1);
  Aabb box{glm::vec3(0, -1, -1), glm::vec3(1, 1, 1)};
  tree.bounds = box;
  for (uint32_t i = 0; i < kChain; ++i) {
    const float split = 1.0f - float(i + 1) / 128.0f;
    KdNode& n = tree.nodes[i];
    n.axis = 0;
    n.split = split;
    n.box = box;
    n.parent = i == 0 ? kNoHit : i - 1;
    n.rightChild = 2 * kChain - i;
    KdNode& r = tree.nodes[n.rightChild];
    r.parent = i;
    r.box = box;
    r.box.min.x = split;
    const float x = split + 0.25f / 128.0f;  // a wall inside the right leaf
    r.firstRef = static_cast<uint32_t>(tree.references.size());
    r.refCount = 1;
    tree.references.push_back(static_cast<uint32_t>(tris.size()));
    tris.push_back({glm::vec3(x, -1, -1), glm::vec3(x, 2, -1), glm::vec3(x, -1, 2)});
    box.max.x = split;
  }
  tree.nodes[kChain].parent = kChain - 1;
  tree.nodes[kChain].box = box;
  const Ray ray{glm::vec3(-1, 0.1f, 0.1f), glm::vec3(1, 0, 0)};
  RayStats stats;
  const Hit hit = traverseKdTree(tree, tris, ray, false, &stats);
  const Hit brute = intersectBruteForce(tris, ray, false);
  ASSERT_TRUE(hit.found());
  EXPECT_EQ(hit.id, brute.id);
  EXPECT_EQ(hit.id, kChain - 1);  // the deepest split's right leaf is nearest
  EXPECT_EQ(stats.triangleTests, 1u);
  const Ray back{glm::vec3(2, 0.1f, 0.1f), glm::vec3(-1, 0, 0)};
  EXPECT_EQ(traverseKdTree(tree, tris, back, false).id, 0u);
}

}  // namespace
}  // namespace passtrace
