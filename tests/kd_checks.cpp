#include "tests/kd_checks.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iterator>

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "tests/hit_checks.h"

namespace passtrace::test::kd {
namespace {

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

}  // namespace

std::vector<NamedMesh> kdMeshes() {
  std::vector<NamedMesh> meshes = testmesh::standardMeshes();
  meshes.push_back({"stackedGrids", stackedGrids()});
  meshes.push_back({"quadCube", quadCube()});
  meshes.push_back({"largeAndSmall", largeAndSmall()});
  return meshes;
}

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

}  // namespace passtrace::test::kd
