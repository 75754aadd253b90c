// Kd-trees: the SAH builder (CPU accelerator 2), the pbrt builder (3), the
// stack traversal, and the restart/backtrack texel layouts. Against brute
// force the traversal may differ only in which of several triangles hit at
// the same t wins; the rays include the ones kd-trees get wrong most easily:
// parallel to split planes, and starting exactly on them.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/kd/kd_structures.h"
#include "accel/registry.h"
#include "tests/registry_helpers.h"
#include "accel/kd/kd_texels.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "accel/reference_lists.h"
#include "stream/texel_address.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;

bool tiedT(float a, float b) { return std::fabs(a - b) <= 1e-6f * std::max(std::fabs(a), std::fabs(b)); }

std::vector<Triangle> concat(std::initializer_list<std::vector<Triangle>> parts) {
  std::vector<Triangle> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Flat grids stacked along z at quarter steps, plus one along x: every grid
// is a plane the SAH likes to split on, so triangles lie exactly in split
// planes and rays start on them.
std::vector<Triangle> stackedGrids() {
  return concat({testmesh::flatGrid(6, 6, 2, 0.0f), testmesh::flatGrid(6, 6, 2, 0.25f),
                 testmesh::flatGrid(5, 7, 2, 0.5f), testmesh::flatGrid(6, 6, 2, 1.0f),
                 testmesh::flatGrid(4, 4, 0, 0.5f)});
}

// The unit cube's six faces as 4x4 quads, with a quad wall through the middle.
std::vector<Triangle> quadCube() {
  std::vector<std::vector<Triangle>> parts;
  for (int axis = 0; axis < 3; ++axis)
    for (const float offset : {0.0f, 1.0f}) parts.push_back(testmesh::flatGrid(4, 4, axis, offset));
  parts.push_back(testmesh::flatGrid(4, 4, 1, 0.5f));
  std::vector<Triangle> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Small triangles and a few that span the whole scene (larger than any voxel).
std::vector<Triangle> largeAndSmall() {
  std::vector<Triangle> tris = testmesh::triangleSoup(1500, Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)}, 0.08f, 3);
  tris.push_back({glm::vec3(-1, -1, -1), glm::vec3(1, -1, 1), glm::vec3(-1, 1, 1)});
  tris.push_back({glm::vec3(-1, 0.1f, -1), glm::vec3(1, 0.1f, -1), glm::vec3(0, 0.1f, 1)});
  tris.push_back({glm::vec3(-1, 1, -1), glm::vec3(1, -1, -1), glm::vec3(0.3f, 0.2f, 1)});
  tris.push_back(tris[500]);  // a duplicate
  return tris;
}

std::vector<NamedMesh> kdMeshes() {
  std::vector<NamedMesh> meshes = testmesh::standardMeshes();
  meshes.push_back({"stackedGrids", stackedGrids()});
  meshes.push_back({"quadCube", quadCube()});
  meshes.push_back({"largeAndSmall", largeAndSmall()});
  return meshes;
}

enum class Builder { Sah, Pbrt };

KdTree build(Builder b, std::span<const Triangle> tris, const KdBuildConfig* config = nullptr) {
  if (b == Builder::Sah) return buildKdTree(tris, config ? *config : KdBuildConfig{});
  return buildKdTreePbrt(tris, config ? *config : kPbrtKdConfig);
}

// --- triangle/box overlap for the completeness check -------------------------------

// Separating-axis test in double precision (box normals, triangle normal, the
// nine edge cross products). Zero axes (degenerate triangles) separate nothing.
bool triangleOverlapsBox(const Triangle& tri, const Aabb& box) {
  const glm::dvec3 c = (glm::dvec3(box.min) + glm::dvec3(box.max)) * 0.5;
  const glm::dvec3 h = (glm::dvec3(box.max) - glm::dvec3(box.min)) * 0.5;
  const glm::dvec3 v[3] = {glm::dvec3(tri.v0) - c, glm::dvec3(tri.v1) - c, glm::dvec3(tri.v2) - c};
  auto separates = [&](const glm::dvec3& axis) {
    const double p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
    const double r = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 a(0.0);
    a[k] = 1.0;
    if (separates(a)) return false;
    for (const auto& edge : e)
      if (separates(glm::cross(a, edge))) return false;
  }
  return !separates(glm::cross(e[0], e[1]));
}

// The voxel pulled in by a hair (at most a quarter of its extent) along its
// non-flat dimensions: a triangle overlapping this certainly overlaps the
// voxel's interior there, whatever the rounding, which pbrt's trees (whose
// children get only triangles reaching past the plane) require too.
Aabb shrunk(const Aabb& voxel, float margin) {
  Aabb b = voxel;
  for (int k = 0; k < 3; ++k) {
    const float m = std::min(margin, 0.25f * (voxel.max[k] - voxel.min[k]));
    b.min[k] += m;
    b.max[k] -= m;
  }
  return b;
}

bool boundsTouch(const Aabb& a, const Aabb& b) {
  return glm::all(glm::lessThanEqual(a.min, b.max)) && glm::all(glm::lessThanEqual(b.min, a.max));
}

// Structure: depth-first layout, parents, children's voxels splitting the
// parent's exactly (so the leaves tile the root), reference ranges; and
// completeness: every triangle that really overlaps a leaf's voxel (less a
// hair) is in its list, and every listed triangle's bounds touch the voxel.
void expectValidKdTree(const KdTree& tree, std::span<const Triangle> tris, const std::string& what) {
  SCOPED_TRACE(what);
  if (tris.empty()) {
    EXPECT_TRUE(tree.nodes.empty());
    return;
  }
  ASSERT_FALSE(tree.nodes.empty());
  const Aabb bounds = testmesh::boundsOf(tris);
  EXPECT_EQ(tree.bounds.min, bounds.min);
  EXPECT_EQ(tree.bounds.max, bounds.max);
  EXPECT_EQ(tree.nodes[0].box.min, bounds.min);
  EXPECT_EQ(tree.nodes[0].box.max, bounds.max);
  EXPECT_EQ(tree.nodes[0].parent, kNoHit);

  std::vector<int> seen(tree.nodes.size(), 0);
  std::vector<uint32_t> stack{0};
  size_t refTotal = 0;
  std::vector<std::pair<uint32_t, uint32_t>> ranges;
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    ASSERT_LT(i, tree.nodes.size());
    ASSERT_EQ(seen[i]++, 0) << "node " << i << " reached twice";
    const KdNode& n = tree.nodes[i];
    if (n.isLeaf()) {
      ASSERT_LE(size_t{n.firstRef} + n.refCount, tree.references.size());
      refTotal += n.refCount;
      ranges.emplace_back(n.firstRef, n.refCount);
      for (uint32_t r = 0; r < n.refCount; ++r) {
        const uint32_t t = tree.references[n.firstRef + r];
        ASSERT_LT(t, tris.size());
        EXPECT_TRUE(boundsTouch(tris[t].bounds(), n.box)) << "leaf " << i << " lists triangle " << t;
      }
      continue;
    }
    ASSERT_LT(n.axis, 3u);
    const uint32_t left = i + 1, right = n.rightChild;
    ASSERT_LT(left, tree.nodes.size());
    ASSERT_LT(right, tree.nodes.size());
    ASSERT_GT(right, left);
    EXPECT_EQ(tree.nodes[left].parent, i);
    EXPECT_EQ(tree.nodes[right].parent, i);
    EXPECT_GT(n.split, n.box.min[n.axis]) << "node " << i;
    EXPECT_LT(n.split, n.box.max[n.axis]) << "node " << i;
    Aabb lb = n.box, rb = n.box;
    lb.max[n.axis] = n.split;
    rb.min[n.axis] = n.split;
    EXPECT_EQ(tree.nodes[left].box.min, lb.min);
    EXPECT_EQ(tree.nodes[left].box.max, lb.max);
    EXPECT_EQ(tree.nodes[right].box.min, rb.min);
    EXPECT_EQ(tree.nodes[right].box.max, rb.max);
    stack.push_back(right);
    stack.push_back(left);
  }
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "node " << i;
  EXPECT_EQ(refTotal, tree.references.size());
  std::sort(ranges.begin(), ranges.end());
  for (size_t k = 1; k < ranges.size(); ++k)
    EXPECT_LE(ranges[k - 1].first + ranges[k - 1].second, ranges[k].first) << "leaf lists overlap";

  // Completeness: walk each triangle down the tree through every child its
  // bounds touch, and at each leaf require the reference when it overlaps.
  const float margin = 1e-5f * std::max(1.0f, glm::length(bounds.extent()));
  size_t missing = 0;
  for (uint32_t t = 0; t < tris.size(); ++t) {
    const Aabb tb = tris[t].bounds();
    std::vector<uint32_t> walk{0};
    while (!walk.empty()) {
      const uint32_t i = walk.back();
      walk.pop_back();
      const KdNode& n = tree.nodes[i];
      if (!boundsTouch(tb, n.box)) continue;
      if (!n.isLeaf()) {
        walk.push_back(i + 1);
        walk.push_back(n.rightChild);
        continue;
      }
      const Aabb inner = shrunk(n.box, margin);
      if (inner.empty() || !triangleOverlapsBox(tris[t], inner)) continue;
      const auto begin = tree.references.begin() + n.firstRef;
      if (std::find(begin, begin + n.refCount, t) == begin + n.refCount) ++missing;
    }
  }
  EXPECT_EQ(missing, 0u) << "triangles overlapping a leaf voxel but not in its list";
}

// Every internal node's triangle set (the union of its children's) must be
// larger than minElements; sets are built bottom-up (children follow parents).
void expectMinElements(const KdTree& tree, size_t minElements) {
  std::vector<std::vector<uint32_t>> sets(tree.nodes.size());
  for (size_t k = tree.nodes.size(); k-- > 0;) {
    const KdNode& n = tree.nodes[k];
    if (n.isLeaf()) {
      sets[k].assign(tree.references.begin() + n.firstRef, tree.references.begin() + n.firstRef + n.refCount);
      std::sort(sets[k].begin(), sets[k].end());
      sets[k].erase(std::unique(sets[k].begin(), sets[k].end()), sets[k].end());
      continue;
    }
    std::set_union(sets[k + 1].begin(), sets[k + 1].end(), sets[n.rightChild].begin(), sets[n.rightChild].end(),
                   std::back_inserter(sets[k]));
    EXPECT_GT(sets[k].size(), minElements) << "internal node " << k;
  }
}

// --- agreement with brute force ---------------------------------------------------

struct Agreement {
  size_t queries = 0, hits = 0, foundMismatch = 0, tieMismatch = 0, bogusAnyHit = 0;
  uint64_t kdTests = 0, bruteTests = 0, kdSteps = 0;
};

Agreement compare(const CpuAccelerator& accel, std::span<const Triangle> tris, std::span<const Ray> rays) {
  Agreement a;
  for (const Ray& ray : rays) {
    for (const bool anyHit : {false, true}) {
      ++a.queries;
      RayStats ks, bs;
      const Hit k = accel.intersect(ray, anyHit, &ks);
      const Hit b = intersectBruteForce(tris, ray, anyHit, &bs);
      a.kdTests += ks.triangleTests;
      a.kdSteps += ks.steps;
      a.bruteTests += bs.triangleTests;
      if (k.found() != b.found()) {
        ++a.foundMismatch;
        continue;
      }
      if (!k.found()) continue;
      ++a.hits;
      if (anyHit) {
        Hit check{ray.tMax};
        if (!intersectTriangle(ray.origin, ray.direction, tris[k.id], k.id, check) || check.t != k.t)
          ++a.bogusAnyHit;
      } else if (k.id != b.id && !tiedT(k.t, b.t)) {
        ++a.tieMismatch;
      }
    }
  }
  return a;
}

void expectAgreement(const Agreement& a, const std::string& what) {
  EXPECT_EQ(a.foundMismatch, 0u) << what;
  EXPECT_EQ(a.tieMismatch, 0u) << what;
  EXPECT_EQ(a.bogusAnyHit, 0u) << what;
}

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

TEST_P(KdMeshTest, TreesAreValidAndComplete) {
  const auto& tris = GetParam().tris;
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, tris);
    expectValidKdTree(tree, tris, GetParam().name + (b == Builder::Sah ? " sah" : " pbrt"));
    EXPECT_LE(tree.depth(), static_cast<uint32_t>(kdDefaultMaxDepth(tris.size())) + 1);
    expectMinElements(tree, b == Builder::Sah ? 2 : 1);
  }
}

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
    std::cout << "[ stats    ] " << what << ": " << tris.size() << " triangles, " << s.nodes << " nodes, " << s.leaves
              << " leaves, " << s.references << " refs, depth " << s.depth << ", " << s.floatsPerTriangle
              << " floats/tri; mix " << a.hits << "/" << a.queries << " hits, tests per query "
              << double(a.kdTests) / double(a.queries) << " (brute " << double(a.bruteTests) / double(a.queries)
              << "); plane rays " << p.hits << "/" << p.queries << " hits\n";
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

TEST_P(KdMeshTest, FlattenedLayoutsMatchTheTree) {
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

INSTANTIATE_TEST_SUITE_P(Meshes, KdMeshTest, ::testing::ValuesIn(kdMeshes()), meshName);

// --- construction ------------------------------------------------------------------

TEST(KdTree, DefaultMaxDepthIsPbrtsFormula) {
  EXPECT_EQ(kdDefaultMaxDepth(0), 8);
  EXPECT_EQ(kdDefaultMaxDepth(1), 8);
  EXPECT_EQ(kdDefaultMaxDepth(2), 9);        // 9.3
  EXPECT_EQ(kdDefaultMaxDepth(32), 15);      // 14.5 rounds up
  EXPECT_EQ(kdDefaultMaxDepth(1024), 21);
  EXPECT_EQ(kdDefaultMaxDepth(69451), 29);   // the bunny: 28.9
  EXPECT_EQ(kdDefaultMaxDepth(100000), 30);  // 29.6
  for (const size_t n : {3u, 100u, 5000u, 1000000u})
    EXPECT_EQ(kdDefaultMaxDepth(n), static_cast<int>(std::lround(8 + 1.3 * std::log2(double(n))))) << n;
  EXPECT_EQ(kdEffectiveMaxDepth(KdBuildConfig{}, 1024), 21);
  EXPECT_EQ(kdEffectiveMaxDepth(KdBuildConfig{.maxDepth = 5}, 1024), 5);
  EXPECT_EQ(kdEffectiveMaxDepth(KdBuildConfig{.maxDepth = 500}, 1024), kKdDepthLimit);
}

TEST(KdTree, MaxDepthAndMinElementsAreRespected) {
  const auto tris = testmesh::triangleSoup(4000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 8);
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    for (const int depth : {1, 3, 6, 12}) {
      KdBuildConfig config = b == Builder::Sah ? KdBuildConfig{} : kPbrtKdConfig;
      config.maxDepth = depth;
      const KdTree tree = build(b, tris, &config);
      EXPECT_LE(tree.depth(), static_cast<uint32_t>(depth) + 1);
      if (depth <= 6) {
        EXPECT_EQ(tree.depth(), static_cast<uint32_t>(depth) + 1) << "a soup splits as deep as allowed";
      }
      expectValidKdTree(tree, tris, "maxDepth " + std::to_string(depth));
    }
    for (const int minElements : {1, 2, 8, 50}) {
      KdBuildConfig config = b == Builder::Sah ? KdBuildConfig{} : kPbrtKdConfig;
      config.minElements = minElements;
      const KdTree tree = build(b, tris, &config);
      expectMinElements(tree, static_cast<size_t>(minElements));
      expectValidKdTree(tree, tris, "minElements " + std::to_string(minElements));
    }
  }
  // Too many to split at all: one leaf with everything.
  KdBuildConfig config;
  config.minElements = 4000;
  const KdTree leaf = buildKdTree(tris, config);
  ASSERT_EQ(leaf.nodes.size(), 1u);
  EXPECT_EQ(leaf.nodes[0].refCount, 4000u);
  EXPECT_EQ(leaf.depth(), 1u);
}

TEST(KdTree, AcceleratorTwoTakesMinElementsAndMaxDepthFromTheBuildConfig) {
  const auto tris = testmesh::triangleSoup(2000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 9);
  AccelBuildConfig config;
  config.kdMaxDepth = 4;
  EXPECT_EQ(testing_registry::cpuStructure(2, tris, config)->stats().depth, 5u);
  EXPECT_EQ(testing_registry::cpuStructure(3, tris, config)->stats().depth, 5u);
  config.kdMaxDepth = 0;
  config.kdMinElements = 3000;
  EXPECT_EQ(testing_registry::cpuStructure(2, tris, config)->stats().nodes, 1u);
  EXPECT_GT(testing_registry::cpuStructure(3, tris, config)->stats().nodes, 1u) << "pbrt keeps its own maxPrims";
  EXPECT_EQ(kdPbrtConfigFor(AccelBuildConfig{}).intersectionCost, 80.0f);
  EXPECT_EQ(kdPbrtConfigFor(AccelBuildConfig{}).minElements, 1);
}

TEST(KdTree, EmptySceneGivesEmptyTreeTexelsAndNoHits) {
  const std::vector<Triangle> none;
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, none);
    EXPECT_TRUE(tree.empty());
    EXPECT_EQ(tree.depth(), 0u);
    const KdTexels tex = flattenKdBacktrack(tree, 0);
    EXPECT_TRUE(tex.nodes.empty());
    EXPECT_TRUE(tex.lists.empty());
    EXPECT_EQ(tex.floatsPerTriangle, 0.0);
    RayStats stats;
    EXPECT_FALSE(traverseKdTree(tree, none, Ray{}, false, &stats).found());
    EXPECT_EQ(stats.steps, 0u);
  }
  const auto accel = testing_registry::cpuStructure(2, none);
  EXPECT_EQ(accel->stats().nodes, 0u);
  EXPECT_EQ(accel->stats().floatsPerTriangle, 0.0);
}

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

TEST(KdTree, DegenerateScenesBuild) {
  // All triangles in one point: nothing to split, one leaf.
  const auto points = testmesh::pointMesh(1000);
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    const KdTree tree = build(b, points);
    ASSERT_EQ(tree.nodes.size(), 1u);
    EXPECT_EQ(tree.nodes[0].refCount, 1000u);
    EXPECT_FALSE(traverseKdTree(tree, points, Ray{glm::vec3(0.5f, 0.5f, -1), glm::vec3(0, 0, 1)}, false).found());
  }
  // All triangles on one line (a segment voxel) and all duplicates of one.
  std::vector<Triangle> line, dups;
  for (int i = 0; i < 300; ++i) {
    const float x = float(i % 17) * 0.1f;
    line.push_back({glm::vec3(x, 1, 2), glm::vec3(x + 0.3f, 1, 2), glm::vec3(x + 0.1f, 1, 2)});
    dups.push_back({glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)});
  }
  for (const Builder b : {Builder::Sah, Builder::Pbrt}) {
    expectValidKdTree(build(b, line), line, "line");
    const KdTree tree = build(b, dups);
    expectValidKdTree(tree, dups, "duplicates");
    const Hit hit = traverseKdTree(tree, dups, Ray{glm::vec3(0.2f, 0.2f, 1), glm::vec3(0, 0, -1)}, false);
    EXPECT_TRUE(hit.found());
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
  }
}

TEST(KdTree, SplitClippingShrinksCandidatesOfLongTriangles) {
  // Long diagonal slivers: their full bounds cover the scene, their clipped
  // bounds do not; clipping must never cost correctness, and should not make
  // the tree worse by the SAH's own measure (fewer references per leaf hit).
  std::vector<Triangle> tris = testmesh::triangleSoup(800, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 12);
  for (int i = 0; i < 40; ++i) {
    const float o = -1.0f + 0.05f * float(i);
    tris.push_back({glm::vec3(-1, o, -1), glm::vec3(1, o + 0.01f, 1), glm::vec3(1, o, 1)});
  }
  KdBuildConfig noClip;
  noClip.splitClipping = false;
  const KdTree clipped = buildKdTree(tris), plain = buildKdTree(tris, noClip);
  expectValidKdTree(clipped, tris, "clipped");
  expectValidKdTree(plain, tris, "plain");
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 8);
  RayStats sc, sp;
  for (const Ray& ray : rays) {
    const Hit a = traverseKdTree(clipped, tris, ray, false, &sc);
    const Hit b = traverseKdTree(plain, tris, ray, false, &sp);
    const Hit c = intersectBruteForce(tris, ray, false);
    EXPECT_EQ(a.found(), c.found());
    EXPECT_EQ(b.found(), c.found());
  }
  std::cout << "[ stats    ] slivers: triangle tests with split clipping " << sc.triangleTests << ", without "
            << sp.triangleTests << "\n";
}

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

// --- size and speed ----------------------------------------------------------------

TEST(KdTree, LargeMeshesBuildAndTimesArePrinted) {
  struct Case {
    std::string name;
    std::vector<Triangle> tris;
  };
  std::vector<Case> cases;
  cases.push_back({"soup100k", testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.05f, 2005)});
  cases.push_back({"sphere70k (bunny-sized)", testmesh::uvSphere(190, 184)});
  cases.push_back({"soup70k (bunny-sized)", testmesh::triangleSoup(69451, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.06f, 6)});
  for (const Case& c : cases) {
    for (const int number : {2, 3}) {
      const auto start = std::chrono::steady_clock::now();
      const auto accel = testing_registry::cpuStructure(number, c.tris);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      const AccelStats s = accel->stats();
      std::cout << "[ build    ] " << c.name << " (" << c.tris.size() << ") " << s.name << ": " << ms << " ms, "
                << s.nodes << " nodes, " << s.leaves << " leaves, " << s.references << " refs ("
                << double(s.references) / double(c.tris.size()) << " per triangle), depth " << s.depth << ", "
                << s.floatsPerTriangle << " floats/tri restart\n";
      EXPECT_GT(s.nodes, 1000u);
      EXPECT_GE(s.buildMs, 0.0);
      // A few rays against brute force.
      const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(c.tris), 25, 3);
      expectAgreement(compare(*accel, c.tris, rays), c.name + " " + s.name);
    }
  }
}

}  // namespace
}  // namespace passtrace
