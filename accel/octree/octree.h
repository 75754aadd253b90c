#pragma once
// An octree over the scene (CPU accelerator 7, thesis Table 4; section 5.1
// discusses octrees among the spatial subdivisions). The root is the cube
// around the scene bounds (edge = their largest extent, same center), so
// every node is a cube and flat scenes still split along all three axes.
// Internal nodes split at their center into eight octants; only non-empty
// octants are stored. Triangles are listed in every leaf whose padded box
// they overlap (triangleOverlapsBox, the uniform grid's test), so the octree
// is a spatial subdivision: traversal is front to back and stops at the
// first leaf holding a hit inside it.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct OctreeConfig {
  // Most levels below the root. 0 picks ceil(log8 N) + 3: a balanced tree
  // needs log8 N levels to get down to a few triangles per leaf, and the
  // extra 3 let it adapt to clustered geometry; clamped to [1, 16].
  int maxDepth = 0;
  // A node with at most this many triangles is a leaf.
  int maxLeafTriangles = 8;
};

struct OctreeNode {
  Aabb box;                 // the node's cube (not fitted to its triangles)
  uint32_t firstChild = 0;  // internal: index of its first child in Octree::nodes
  uint32_t childCount = 0;  // internal: 1-8 contiguous non-empty children; 0 = leaf
  uint32_t firstRef = 0;    // leaf: its triangles are references[firstRef, firstRef + refCount)
  uint32_t refCount = 0;
  bool isLeaf() const { return childCount == 0; }
};

struct Octree {
  std::vector<OctreeNode> nodes;     // nodes[0] is the root; empty for an empty scene
  std::vector<uint32_t> references;  // scene indices, grouped per leaf, increasing within one
  uint32_t depth = 0;                // levels; a root leaf is 1

  size_t leafCount() const {
    size_t n = 0;
    for (const OctreeNode& node : nodes) n += node.isLeaf() ? 1 : 0;
    return n;
  }
  // Memory accounting in the spirit of thesis Table 3 (triangles excluded):
  // 8 floats per node (box, child or list pointer, count) and one float per
  // reference, divided by the triangle count.
  double floatsPerTriangle(size_t triangleCount) const {
    return triangleCount == 0 ? 0.0 : (8.0 * double(nodes.size()) + double(references.size())) / double(triangleCount);
  }
};

// A node becomes a leaf when it holds at most maxLeafTriangles triangles,
// sits at maxDepth, has a zero-size cube (every triangle at one point), or
// when splitting would not separate anything (every non-empty octant would
// hold all of its triangles, e.g. many large overlapping triangles).
// Explicit work stack.
Octree buildOctree(std::span<const Triangle> tris, const OctreeConfig& config = {});

// Front to back: children are visited in order of the t at which the ray
// enters them (an explicit stack, nearest on top); a node entered at or
// beyond best.t is skipped; traversal stops when best.t <= the exit t of the
// leaf just tested, or at the first hit with anyHit. Starts from
// best = Hit{t = ray.tMax}. stats: one step per node visited, one test per
// triangle test (a triangle in several leaves may be tested more than once).
// `test` picks the ray/triangle test (accel/geometry/triangle_test.h).
Hit traverseOctree(const Octree& octree, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                   RayStats* stats = nullptr, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
