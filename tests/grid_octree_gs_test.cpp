// Goldsmith/Salmon BVH (accelerators 1 and 6), uniform grid (4) and octree
// (7): construction invariants, the GPU grid layout, and agreement with
// brute force on the standard meshes plus a mesh built to sit on the grid's
// cell boundaries. Against brute force an accelerator may differ only in
// which of several triangles hit at the same t wins.

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
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/goldsmith_salmon_builder.h"
#include "accel/registry.h"
#include "tests/registry_helpers.h"
#include "accel/grid/grid_texels.h"
#include "accel/grid/grid_traversal.h"
#include "accel/octree/octree.h"
#include "accel/reference_lists.h"
#include "accel/grid/uniform_grid.h"
#include "accel/grid/uniform_grid_builder.h"
#include "tests/bvh_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::expectValidBvh;

using testmesh::NamedMesh;

constexpr int kFamily[] = {1, 4, 6, 7};

bool sameHit(const Hit& a, const Hit& b) { return a.id == b.id && a.t == b.t && a.u == b.u && a.v == b.v; }
bool tiedT(float a, float b) { return std::fabs(a - b) <= 1e-6f * std::max(std::fabs(a), std::fabs(b)); }

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// 64 triangles in [0, 8]^3, so the grid is exactly 8 x 8 x 8 cells of edge 1
// (2 * cbrt(64) = 8): axis-aligned squares lying in cell planes with corners
// on cell corners, triangles spanning the whole box (far larger than a
// cell), and triangles with integer vertices whose edges run along cell
// edges and faces.
std::vector<Triangle> cellBoundaryMesh() {
  std::vector<Triangle> tris;
  auto square = [&](int axis, float p, float a0, float a1, float b0, float b1) {
    auto at = [&](float a, float b) {
      glm::vec3 v;
      v[axis] = p;
      v[(axis + 1) % 3] = a;
      v[(axis + 2) % 3] = b;
      return v;
    };
    tris.push_back({at(a0, b0), at(a1, b0), at(a1, b1)});
    tris.push_back({at(a0, b0), at(a1, b1), at(a0, b1)});
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const float p : {0.0f, 3.0f, 5.0f, 8.0f}) square(axis, p, float(1 + axis), float(4 + axis), 2.0f, 6.0f);
  // 24 so far; four large ones.
  tris.push_back({glm::vec3(0, 0, 0), glm::vec3(8, 0, 8), glm::vec3(0, 8, 8)});
  tris.push_back({glm::vec3(8, 8, 0), glm::vec3(0, 8, 0), glm::vec3(8, 0, 8)});
  tris.push_back({glm::vec3(0, 0, 4), glm::vec3(8, 0, 4), glm::vec3(8, 8, 4)});  // in a cell plane
  tris.push_back({glm::vec3(1, 7, 1), glm::vec3(7, 1, 7), glm::vec3(4, 4, 1)});
  std::mt19937_64 rng(17);
  auto coord = [&] { return float(rng() % 9); };
  while (tris.size() < 64) {
    const glm::vec3 v0(coord(), coord(), coord());
    glm::vec3 v1 = v0, v2 = v0;
    const int a = int(rng() % 3), b = (a + 1 + int(rng() % 2)) % 3;
    v1[a] = coord();
    v2[b] = coord();
    if (rng() % 2) v2[a] = v1[a];  // sometimes a right triangle in a cell plane
    if (glm::cross(v1 - v0, v2 - v0) == glm::vec3(0.0f)) continue;
    tris.push_back({v0, v1, v2});
  }
  return tris;
}

std::vector<NamedMesh> meshes() {
  std::vector<NamedMesh> all = testmesh::standardMeshes();
  all.push_back({"cellBoundaries", cellBoundaryMesh()});
  return all;
}

// Rays whose origins lie exactly on cell boundary planes (computed as the
// grid computes them), in random, axis-aligned and plane-parallel
// directions, some lying in the plane they start on, some aimed inside.
std::vector<Ray> boundaryRays(const UniformGrid& grid, size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Ray> rays;
  const glm::vec3 lo = grid.bounds.min, ext = grid.bounds.extent();
  for (size_t i = 0; i < count; ++i) {
    Ray ray;
    for (int k = 0; k < 3; ++k) ray.origin[k] = lo[k] + unit(rng) * ext[k];
    // One to three coordinates on a boundary (grid corners included).
    const int onPlanes = 1 + int(rng() % 3);
    for (int j = 0; j < onPlanes; ++j) {
      const int k = int(rng() % 3);
      const int boundary = int(rng() % uint64_t(grid.resolution[k] + 1));
      ray.origin[k] = boundary == grid.resolution[k] ? grid.bounds.max[k] : lo[k] + float(boundary) * grid.cellSize[k];
    }
    const int kind = int(rng() % 4);
    glm::vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
    if (glm::dot(d, d) < 1e-6f) d = glm::vec3(1, 0, 0);
    d = glm::normalize(d);
    if (kind == 1) {  // axis aligned
      const int k = int(rng() % 3);
      d = glm::vec3(0.0f);
      d[k] = rng() % 2 ? 1.0f : -1.0f;
    } else if (kind == 2) {  // parallel to one family of cell planes
      const int k = int(rng() % 3);
      d[k] = 0.0f;
      if (glm::dot(d, d) < 1e-6f) d[(k + 1) % 3] = 1.0f;
      d = glm::normalize(d);
      d[k] = 0.0f;
    } else if (kind == 3) {  // at a random point inside the bounds
      glm::vec3 target;
      for (int k = 0; k < 3; ++k) target[k] = lo[k] + unit(rng) * ext[k];
      if (target != ray.origin) d = glm::normalize(target - ray.origin);
    }
    ray.direction = d;
    if (rng() % 3 == 0) ray.tMax = unit(rng) * glm::length(ext);
    rays.push_back(ray);
  }
  return rays;
}

struct Agreement {
  size_t rays = 0, hits = 0, foundMismatch = 0, tieMismatch = 0, bogusAnyHit = 0;
  uint64_t steps = 0, tests = 0;
};

Agreement compareWithBruteForce(const CpuAccelerator& accel, std::span<const Triangle> tris,
                                std::span<const Ray> rays) {
  Agreement a;
  for (const Ray& ray : rays)
    for (const bool anyHit : {false, true}) {
      ++a.rays;
      RayStats stats;
      const Hit h = accel.intersect(ray, anyHit, &stats);
      const Hit b = intersectBruteForce(tris, ray, anyHit);
      a.steps += stats.steps;
      a.tests += stats.triangleTests;
      if (h.found() != b.found()) {
        ++a.foundMismatch;
        continue;
      }
      if (!h.found()) continue;
      ++a.hits;
      if (anyHit) {
        Hit check{ray.tMax};
        if (!intersectTriangle(ray.origin, ray.direction, tris[h.id], h.id, check) || !sameHit(check, h))
          ++a.bogusAnyHit;
      } else if (h.id != b.id && !tiedT(h.t, b.t)) {
        ++a.tieMismatch;
      }
    }
  return a;
}

bool sameTree(const Bvh& a, const Bvh& b) {
  if (a.nodes.size() != b.nodes.size() || a.children != b.children) return false;
  for (size_t n = 0; n < a.nodes.size(); ++n) {
    const BvhNode &x = a.nodes[n], &y = b.nodes[n];
    if (x.triangle != y.triangle || x.firstChild != y.firstChild || x.childCount != y.childCount ||
        x.box.min != y.box.min || x.box.max != y.box.max)
      return false;
  }
  return true;
}

// --- per-mesh agreement -----------------------------------------------------------

class GridOctreeGsMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(GridOctreeGsMeshTest, AgreesWithBruteForce) {
  const auto& tris = GetParam().tris;
  const UniformGrid grid = buildUniformGrid(tris);
  std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 1000, 42);
  const std::vector<Ray> edge = boundaryRays(grid, 2000, 9);
  rays.insert(rays.end(), edge.begin(), edge.end());
  for (const int number : kFamily) {
    const auto accel = testing_registry::cpuStructure(number, tris);
    const Agreement a = compareWithBruteForce(*accel, tris, rays);
    const std::string what = GetParam().name + " / " + accel->name();
    EXPECT_EQ(a.foundMismatch, 0u) << what;
    EXPECT_EQ(a.tieMismatch, 0u) << what;
    EXPECT_EQ(a.bogusAnyHit, 0u) << what;
    EXPECT_GT(a.hits, 0u) << what;
    std::cout << "[ stats    ] " << what << ": " << a.hits << " of " << a.rays << " queries hit, steps "
              << double(a.steps) / double(a.rays) << ", triangle tests " << double(a.tests) / double(a.rays)
              << " per query\n";
  }
}

TEST_P(GridOctreeGsMeshTest, GoldsmithSalmonSequentialAndRecursiveAgreeExactly) {
  const auto& tris = GetParam().tris;
  const auto sequential = testing_registry::cpuStructure(1, tris);
  const auto recursive = testing_registry::cpuStructure(6, tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 500, 3);
  size_t differ = 0, stepDiffer = 0;
  for (const Ray& ray : rays)
    for (const bool anyHit : {false, true}) {
      RayStats s, r;
      differ += !sameHit(sequential->intersect(ray, anyHit, &s), recursive->intersect(ray, anyHit, &r));
      stepDiffer += s.steps != r.steps || s.triangleTests != r.triangleTests;
    }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(stepDiffer, 0u);
  const AccelStats a = sequential->stats(), b = recursive->stats();
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.name, "gs-bvh");
  EXPECT_EQ(b.name, "gs-bvh-recursive");
}

TEST_P(GridOctreeGsMeshTest, GoldsmithSalmonGreedyTreeIsValidAndAgrees) {
  const auto& tris = GetParam().tris;
  double cost = -1.0;
  const Bvh bvh = buildGoldsmithSalmon(tris, {.tries = 3, .search = GoldsmithSalmonSearch::Greedy}, &cost);
  expectValidBvh(bvh, tris);
  EXPECT_NEAR(cost, goldsmithSalmonCost(bvh), 1e-9 * std::max(1.0, cost));
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 8);
  size_t wrong = 0;
  for (const Ray& ray : rays) {
    const Hit h = traverseBvhRecursive(bvh, tris, ray, false), b = intersectBruteForce(tris, ray, false);
    wrong += h.found() != b.found() || (h.found() && h.id != b.id && !tiedT(h.t, b.t));
  }
  EXPECT_EQ(wrong, 0u);
}

TEST_P(GridOctreeGsMeshTest, GoldsmithSalmonTreeIsValid) {
  const auto& tris = GetParam().tris;
  double cost = -1.0;
  const Bvh bvh = buildGoldsmithSalmon(tris, {}, &cost);
  expectValidBvh(bvh, tris);
  EXPECT_EQ(bvh.leafCount(), tris.size());
  EXPECT_NEAR(cost, goldsmithSalmonCost(bvh), 1e-9 * std::max(1.0, cost));
  for (const BvhNode& n : bvh.nodes) EXPECT_LE(n.childCount, 16u);
  // Flattening works on the n-ary tree: 2 texels per box, 3 per triangle.
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  EXPECT_EQ(seq.texels.size(), 2 * bvh.internalCount() + 3 * tris.size());
  std::cout << "[ stats    ] " << GetParam().name << ": G/S depth " << bvh.depth() << ", boxes "
            << bvh.internalCount() << ", floats/triangle " << seq.floatsPerTriangle() << ", cost " << cost << "\n";
}

TEST_P(GridOctreeGsMeshTest, GridListsEveryCellTheTriangleOverlaps) {
  const auto& tris = GetParam().tris;
  const UniformGrid grid = buildUniformGrid(tris);
  ASSERT_EQ(grid.cellStart.size(), grid.cellCount() + 1);
  ASSERT_EQ(grid.cellStart.back(), grid.references.size());
  const glm::vec3 pad = cellPadding(grid);
  size_t checked = 0;
  // Brute force over all (cell, triangle) pairs; the big meshes are sampled.
  const size_t stride = std::max<size_t>(1, grid.cellCount() * tris.size() / 4'000'000);
  for (size_t c = 0; c < grid.cellCount(); c += stride) {
    const glm::ivec3 cell(int(c % grid.resolution.x), int(c / grid.resolution.x % grid.resolution.y),
                          int(c / (size_t(grid.resolution.x) * grid.resolution.y)));
    ASSERT_EQ(grid.cellIndex(cell), c);
    const std::set<uint32_t> listed(grid.references.begin() + grid.cellStart[c],
                                    grid.references.begin() + grid.cellStart[c + 1]);
    EXPECT_TRUE(std::is_sorted(grid.references.begin() + grid.cellStart[c], grid.references.begin() + grid.cellStart[c + 1]));
    EXPECT_EQ(listed.size(), grid.referenceCount(c)) << "a triangle listed twice in one cell";
    const Aabb exact = grid.cellBox(cell);
    const Aabb padded{exact.min - pad, exact.max + pad};
    for (uint32_t t = 0; t < tris.size(); ++t) {
      ++checked;
      const bool degenerate = glm::cross(tris[t].v1 - tris[t].v0, tris[t].v2 - tris[t].v0) == glm::vec3(0.0f);
      const Aabb b = tris[t].bounds();
      const bool touchesPadded = glm::all(glm::lessThanEqual(padded.min, b.max)) &&
                                 glm::all(glm::greaterThanEqual(padded.max, b.min));
      if (triangleOverlapsBox(tris[t], exact)) {
        EXPECT_TRUE(listed.count(t)) << "cell " << c << " misses triangle " << t;
      }
      if (listed.count(t)) {
        EXPECT_TRUE(degenerate ? touchesPadded : triangleOverlapsBox(tris[t], padded))
            << "cell " << c << " lists triangle " << t << " that does not overlap it";
      }
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST_P(GridOctreeGsMeshTest, OctreeIsValid) {
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
  std::cout << "[ stats    ] " << GetParam().name << ": octree nodes " << tree.nodes.size() << ", leaves "
            << tree.leafCount() << ", references " << tree.references.size() << ", depth " << tree.depth << "\n";
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Meshes, GridOctreeGsMeshTest, ::testing::ValuesIn(meshes()), meshName);

// --- Goldsmith/Salmon -------------------------------------------------------------

TEST(GoldsmithSalmon, DeterministicForASeedAndSeedsMatter) {
  const auto tris = testmesh::triangleSoup(3000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 21);
  const Bvh a = buildGoldsmithSalmon(tris, {.tries = 3, .seed = 1234});
  const Bvh b = buildGoldsmithSalmon(tris, {.tries = 3, .seed = 1234});
  const Bvh c = buildGoldsmithSalmon(tris, {.tries = 3, .seed = 4321});
  EXPECT_TRUE(sameTree(a, b));
  EXPECT_FALSE(sameTree(a, c));
}

TEST(GoldsmithSalmon, ThreadCountDoesNotChangeTheTree) {
  const auto tris = testmesh::triangleSoup(2000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 4);
  const Bvh one = buildGoldsmithSalmon(tris, {.tries = 5, .threads = 1});
  EXPECT_TRUE(sameTree(one, buildGoldsmithSalmon(tris, {.tries = 5, .threads = 3})));
  EXPECT_TRUE(sameTree(one, buildGoldsmithSalmon(tris, {.tries = 5, .threads = 8})));
}

TEST(GoldsmithSalmon, BranchAndBoundIsNoWorseThanGreedy) {
  for (const NamedMesh& mesh : meshes()) {
    double greedy = 0, exact = 0;
    buildGoldsmithSalmon(mesh.tris, {.tries = 1, .search = GoldsmithSalmonSearch::Greedy}, &greedy);
    buildGoldsmithSalmon(mesh.tris, {.tries = 1, .search = GoldsmithSalmonSearch::BranchAndBound}, &exact);
    // Each insertion is at least as cheap, though the trees then diverge, so
    // allow a little slack per mesh.
    EXPECT_LE(exact, 1.05 * greedy) << mesh.name;
  }
}

TEST(GoldsmithSalmon, MoreTriesAreNeverWorseAndTheFirstTryIsShared) {
  for (const NamedMesh& mesh : meshes()) {
    double one = 0, ten = 0, oneAgain = 0;
    const Bvh first = buildGoldsmithSalmon(mesh.tris, {.tries = 1, .seed = 77}, &one);
    buildGoldsmithSalmon(mesh.tris, {.tries = 10, .seed = 77}, &ten);
    buildGoldsmithSalmon(mesh.tris, {.tries = 1, .seed = 77}, &oneAgain);
    EXPECT_LE(ten, one) << mesh.name;
    EXPECT_EQ(one, oneAgain) << mesh.name;
    EXPECT_EQ(one, goldsmithSalmonCost(first)) << mesh.name;
  }
  // On a real mesh the shuffles differ and the best of ten is usually better.
  const auto soup = testmesh::triangleSoup(2000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.2f, 5);
  double one = 0, ten = 0;
  buildGoldsmithSalmon(soup, {.tries = 1}, &one);
  buildGoldsmithSalmon(soup, {.tries = 10}, &ten);
  EXPECT_LT(ten, one);
}

TEST(GoldsmithSalmon, BuildsNaryTreesCheaperThanKayKajiya) {
  const auto sphere = testmesh::uvSphere(48, 64);
  double cost = 0;
  const Bvh gs = buildGoldsmithSalmon(sphere, {}, &cost);
  uint32_t widest = 0;
  for (const BvhNode& n : gs.nodes) widest = std::max(widest, n.childCount);
  EXPECT_GT(widest, 2u) << "Goldsmith/Salmon nodes may have any number of children";
  EXPECT_LT(gs.internalCount(), sphere.size() - 1) << "fewer boxes than a binary tree";
  const double kk = goldsmithSalmonCost(buildKayKajiya(sphere));
  std::cout << "[ stats    ] sphere " << sphere.size() << " triangles: G/S cost " << cost << " (K/K tree " << kk
            << "), widest node " << widest << ", depth " << gs.depth() << "\n";
  EXPECT_LT(cost, 1.1 * kk) << "the G/S tree should be about as good as K/K by its own measure";
}

TEST(GoldsmithSalmon, FloatsPerTriangleIsEightPerBox) {
  for (const NamedMesh& mesh : meshes()) {
    const SequenceBuild build = buildGoldsmithSalmonSequence(mesh.tris);
    const Bvh bvh = buildGoldsmithSalmon(mesh.tris);
    EXPECT_EQ(build.sequence.boxCount, bvh.internalCount()) << mesh.name;
    EXPECT_FLOAT_EQ(build.stats.floatsPerTriangle, 8.0 * double(bvh.internalCount()) / double(mesh.tris.size()))
        << mesh.name;
    EXPECT_EQ(build.stats.name, "gs-bvh");
    EXPECT_EQ(build.stats.leaves, mesh.tris.size());
    EXPECT_EQ(build.stats.references, mesh.tris.size());
  }
  // Thesis Table 3 reports 3.6-5.0 for G/S; an n-ary tree always has fewer
  // boxes than the binary 8 (N - 1) / N.
  const auto soup = testmesh::triangleSoup(5000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.1f, 3);
  const double fpt = buildGoldsmithSalmonSequence(soup).stats.floatsPerTriangle;
  std::cout << "[ stats    ] soup 5000: G/S floats per triangle " << fpt << "\n";
  EXPECT_LT(fpt, 8.0 * 4999.0 / 5000.0);
}

TEST(GoldsmithSalmon, CoincidentGeometryStaysShallow) {
  const auto points = testmesh::pointMesh(20000);
  for (const auto search : {GoldsmithSalmonSearch::Greedy, GoldsmithSalmonSearch::BranchAndBound}) {
    const auto start = std::chrono::steady_clock::now();
    const Bvh bvh = buildGoldsmithSalmon(points, {.tries = 2, .search = search});
    const double ms = msSince(start);
    expectValidBvh(bvh, points);
    EXPECT_LE(bvh.depth(), 12u) << "maxChildren and the tie-breaks keep it balanced";
    std::cout << "[ stats    ] 20000 coincident points: depth " << bvh.depth() << ", " << ms << " ms\n";
  }
}

TEST(GoldsmithSalmon, EmptyAndSingle) {
  const std::vector<Triangle> none;
  double cost = -1;
  EXPECT_TRUE(buildGoldsmithSalmon(none, {}, &cost).empty());
  EXPECT_EQ(cost, 0.0);
  const auto one = testmesh::singleTriangle();
  const Bvh bvh = buildGoldsmithSalmon(one, {}, &cost);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].triangle, 0u);
  EXPECT_EQ(cost, 0.0);
}

// --- uniform grid -----------------------------------------------------------------

TEST(UniformGrid, ResolutionFollowsTheShortestAxis) {
  // A 2 x 1 x 1 box and 1000 triangles: 2 cbrt(1000) = 20 along y and z, 40 along x.
  const Aabb box{glm::vec3(0), glm::vec3(2, 1, 1)};
  EXPECT_EQ(gridResolution(box, 1000), glm::ivec3(40, 20, 20));
  EXPECT_EQ(gridResolution(box, 1000, 0.5f), glm::ivec3(20, 10, 10));
  EXPECT_EQ(gridResolution(box, 1000, 1.5f), glm::ivec3(60, 30, 30));
  // The shortest axis may be any of them; 8 triangles give 4 along it.
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(0), glm::vec3(3, 6, 1)}, 8), glm::ivec3(12, 24, 4));
  // Flat axes get one cell; the shortest non-flat axis sets the edge.
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(0), glm::vec3(2, 1, 0)}, 1000), glm::ivec3(40, 20, 1));
  EXPECT_EQ(gridResolution(Aabb{glm::vec3(1), glm::vec3(1)}, 1000), glm::ivec3(1));
  EXPECT_EQ(gridResolution(box, 1, 0.01f), glm::ivec3(2, 1, 1)) << "at least one cell";
  EXPECT_EQ(gridResolution(box, 0), glm::ivec3(0));
  // A needle: the rule would ask for 20 x 2e6 x 20 cells; the cap holds.
  const glm::ivec3 needle = gridResolution(Aabb{glm::vec3(0), glm::vec3(1e-4f, 10.0f, 1e-4f)}, 1000);
  EXPECT_LE(double(needle.x) * needle.y * needle.z, double(maxGridCells(1000)));
  EXPECT_GE(needle.y, 1000);
  // Built grids use the rule: the boundary mesh has exactly 8^3 unit cells.
  const UniformGrid grid = buildUniformGrid(cellBoundaryMesh());
  EXPECT_EQ(grid.resolution, glm::ivec3(8));
  EXPECT_EQ(grid.cellSize, glm::vec3(1.0f));
  EXPECT_EQ(buildUniformGrid(cellBoundaryMesh(), {.multiplier = 0.5f}).resolution, glm::ivec3(4));
}

TEST(UniformGrid, BoundaryTrianglesGoToBothCells) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  // Triangle 26 lies in the plane z = 4, between cell layers 3 and 4.
  auto listed = [&](glm::ivec3 c, uint32_t t) {
    const size_t i = grid.cellIndex(c);
    return std::count(grid.references.begin() + grid.cellStart[i], grid.references.begin() + grid.cellStart[i + 1], t) == 1;
  };
  EXPECT_TRUE(listed({6, 2, 3}, 26));
  EXPECT_TRUE(listed({6, 2, 4}, 26));
  EXPECT_FALSE(listed({6, 2, 5}, 26));
  // Triangle 0 lies in x = 0 (the grid's min face) over y 1..4, z 2..6.
  EXPECT_TRUE(listed({0, 1, 2}, 0));
  EXPECT_FALSE(listed({1, 1, 2}, 0));
}

TEST(UniformGrid, DegenerateTrianglesAreListedByTheirBounds) {
  std::vector<Triangle> tris = testmesh::singleTriangle();  // z = 0, x, y in [-1, 1]
  tris.push_back({glm::vec3(0.1f, 0.1f, 0.0f), glm::vec3(0.1f, 0.1f, 0.0f), glm::vec3(0.1f, 0.1f, 0.0f)});
  tris.push_back({glm::vec3(-0.9f, -0.9f, 0.0f), glm::vec3(0.9f, 0.9f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0f)});
  const UniformGrid grid = buildUniformGrid(tris);
  EXPECT_EQ(grid.resolution.z, 1);
  size_t pointRefs = 0, lineRefs = 0;
  for (uint32_t r : grid.references) {
    pointRefs += r == 1;
    lineRefs += r == 2;
  }
  EXPECT_GE(pointRefs, 1u);
  EXPECT_GE(lineRefs, size_t(grid.resolution.x));
  const auto none = buildUniformGrid(testmesh::pointMesh(100));
  EXPECT_EQ(none.resolution, glm::ivec3(1));
  EXPECT_EQ(none.references.size(), 100u);
  EXPECT_FALSE(traverseGrid(none, testmesh::pointMesh(100), Ray{glm::vec3(0.5f, 0.5f, -1), glm::vec3(0, 0, 1)}, false).found());
}

TEST(UniformGrid, FlattenLayoutIsWhatTheKernelReads) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  const GridTexels texels = flattenGrid(grid, tris.size());
  ASSERT_EQ(texels.cells.size(), (grid.cellCount() + 3) / 4);
  size_t nonEmpty = 0;
  std::vector<float> entries(texels.lists.size() * 4);
  for (size_t j = 0; j < entries.size(); ++j) entries[j] = texels.lists[j >> 2][int(j & 3)];
  for (size_t c = 0; c < grid.cellCount(); ++c) {
    const float start = texels.cells[c >> 2][int(c & 3)];
    if (grid.referenceCount(c) == 0) {
      EXPECT_EQ(start, kListEnd) << "cell " << c;
      continue;
    }
    ++nonEmpty;
    ASSERT_GE(start, 0.0f);
    uint32_t j = unpackIndex(start);
    for (uint32_t r = grid.cellStart[c]; r < grid.cellStart[c + 1]; ++r, ++j) {
      ASSERT_LT(j, entries.size());
      EXPECT_EQ(unpackIndex(entries[j]), grid.references[r]);
    }
    EXPECT_EQ(entries[j], kListEnd);
  }
  for (size_t c = grid.cellCount(); c < 4 * texels.cells.size(); ++c) EXPECT_EQ(texels.cells[c >> 2][int(c & 3)], kListEnd);
  EXPECT_EQ(texels.listEntries, grid.references.size() + nonEmpty);
  EXPECT_EQ(texels.lists.size(), (texels.listEntries + 3) / 4);
  EXPECT_DOUBLE_EQ(texels.floatsPerTriangle, double(grid.cellCount() + texels.listEntries) / double(tris.size()));
  // The accelerator reports the same numbers without flattening.
  const AccelStats s = testing_registry::cpuStructure(4, tris)->stats();
  EXPECT_EQ(s.name, "grid");
  EXPECT_EQ(s.nodes, grid.cellCount());
  EXPECT_EQ(s.leaves, nonEmpty);
  EXPECT_EQ(s.references, grid.references.size());
  EXPECT_EQ(s.depth, 1u);
  EXPECT_DOUBLE_EQ(s.floatsPerTriangle, texels.floatsPerTriangle);
  // An empty grid flattens to nothing.
  const GridTexels empty = flattenGrid(buildUniformGrid({}), 0);
  EXPECT_TRUE(empty.cells.empty());
  EXPECT_EQ(empty.floatsPerTriangle, 0.0);
}

TEST(UniformGrid, TraversalVisitsCellsInOrderAndStopsAtTheFirstHitCell) {
  const auto tris = cellBoundaryMesh();
  const UniformGrid grid = buildUniformGrid(tris);
  // Down the +x axis through the middle of row (y, z) = (6.5, 7.5): nothing
  // there but the big triangles; all 8 cells of the row without a hit, or
  // fewer when one is hit.
  RayStats stats;
  const Ray ray{glm::vec3(-1.0f, 0.5f, 7.5f), glm::vec3(1, 0, 0)};
  const Hit h = traverseGrid(grid, tris, ray, false, &stats);
  const Hit b = intersectBruteForce(tris, ray, false);
  EXPECT_EQ(h.id, b.id);
  EXPECT_LE(stats.steps, 8u);
  // A ray starting inside, exactly on a cell corner, parallel to two axes.
  const Ray corner{glm::vec3(3.0f, 3.0f, 3.0f), glm::vec3(0, 0, 1)};
  EXPECT_EQ(traverseGrid(grid, tris, corner, false).id, intersectBruteForce(tris, corner, false).id);
  // Missing the grid entirely costs nothing.
  RayStats none;
  EXPECT_FALSE(traverseGrid(grid, tris, Ray{glm::vec3(-1), glm::vec3(-1, 0, 0)}, false, &none).found());
  EXPECT_EQ(none.steps, 0u);
}

// --- octree ------------------------------------------------------------------------

TEST(Octree, FloatsPerTriangleAndLimits) {
  const auto tris = testmesh::triangleSoup(4000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.05f, 8);
  const Octree tree = buildOctree(tris, {.maxDepth = 3, .maxLeafTriangles = 4});
  EXPECT_LE(tree.depth, 4u);
  EXPECT_DOUBLE_EQ(tree.floatsPerTriangle(tris.size()),
                   (8.0 * double(tree.nodes.size()) + double(tree.references.size())) / 4000.0);
  const AccelStats s = testing_registry::cpuStructure(7, tris)->stats();
  const Octree byDefault = buildOctree(tris);
  EXPECT_EQ(s.name, "octree");
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

// --- factory and scale -------------------------------------------------------------

TEST(GridFamily, FactoryAndEmptyScenes) {
  const std::vector<Triangle> none;
  const std::vector<Triangle> single = testmesh::singleTriangle();
  for (const int number : kFamily) {
    const auto accel = testing_registry::cpuStructure(number, none);
    RayStats stats;
    EXPECT_FALSE(accel->intersect(Ray{}, false, &stats).found());
    EXPECT_EQ(stats.steps, 0u);
    EXPECT_EQ(accel->name(), testing_registry::cpuName(number));
    const auto viaMain = testing_registry::cpuStructure(number, single);
    EXPECT_EQ(viaMain->name(), testing_registry::cpuName(number));
    EXPECT_TRUE(viaMain->intersect(Ray{glm::vec3(-0.5f, -0.5f, 2.0f), glm::vec3(0, 0, -1)}, false, nullptr).found());
  }
}

TEST(GridFamily, LargeSoupBuildsInReasonableTime) {
  const auto tris = testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.03f, 99);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 500, 1);
  for (const int number : kFamily) {
    const auto start = std::chrono::steady_clock::now();
    const auto accel = testing_registry::cpuStructure(number, tris);
    const double ms = msSince(start);
    const AccelStats s = accel->stats();
    RayStats rs;
    const auto traceStart = std::chrono::steady_clock::now();
    size_t hits = 0;
    for (const Ray& ray : rays) hits += accel->intersect(ray, false, &rs).found();
    const double traceMs = msSince(traceStart);
    std::cout << "[ timing   ] 100k soup " << s.name << ": build " << ms << " ms (stats " << s.buildMs
              << " ms), nodes " << s.nodes << ", leaves " << s.leaves << ", refs " << s.references << ", depth "
              << s.depth << ", floats/tri " << s.floatsPerTriangle << "; " << rays.size() << " rays "
              << traceMs << " ms, " << double(rs.steps) / double(rays.size()) << " steps, "
              << double(rs.triangleTests) / double(rays.size()) << " tests per ray, " << hits << " hits\n";
    EXPECT_GT(hits, 0u);
  }
}

}  // namespace
}  // namespace passtrace
