#pragma once
// Shared by the kd-tree tests: the meshes they run on (the standard ones plus
// the cases kd-trees get wrong most easily), the two builders, the tree's
// structural and completeness checks, and agreement with brute force, where
// the traversal may differ only in which of several triangles hit at the
// same t wins.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "accel/cpu_accelerator.h"
#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"
#include "accel/kd/kd_tree_pbrt_builder.h"
#include "tests/test_meshes.h"

namespace passtrace::test::kd {

using testmesh::NamedMesh;

// The standard meshes plus stacked flat grids (triangles in split planes), a
// cube of quads with a wall through it, and large triangles among small ones.
std::vector<NamedMesh> kdMeshes();

enum class Builder { Sah, Pbrt };

inline KdTree build(Builder b, std::span<const Triangle> tris, const KdBuildConfig* config = nullptr) {
  if (b == Builder::Sah) return buildKdTree(tris, config ? *config : KdBuildConfig{});
  return buildKdTreePbrt(tris, config ? *config : kPbrtKdConfig);
}

// Structure: depth-first layout, parents, children's voxels splitting the
// parent's exactly (so the leaves tile the root), reference ranges; and
// completeness: every triangle that really overlaps a leaf's voxel (less a
// hair) is in its list, and every listed triangle's bounds touch the voxel.
void expectValidKdTree(const KdTree& tree, std::span<const Triangle> tris, const std::string& what);

// Every internal node's triangle set (the union of its children's) must be
// larger than minElements.
void expectMinElements(const KdTree& tree, size_t minElements);

struct Agreement {
  size_t queries = 0, hits = 0, foundMismatch = 0, tieMismatch = 0, bogusAnyHit = 0;
  uint64_t kdTests = 0, bruteTests = 0, kdSteps = 0;
};

Agreement compare(const CpuAccelerator& accel, std::span<const Triangle> tris, std::span<const Ray> rays);
void expectAgreement(const Agreement& a, const std::string& what);

}  // namespace passtrace::test::kd
