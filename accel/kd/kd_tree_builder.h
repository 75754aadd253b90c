#pragma once
// The surface-area-heuristic kd-tree builder of thesis section 8.1 and 8.4:
// Haines's cost with split clipping (Havran), split candidates at the bounds
// of every triangle clipped to the node's voxel.
//
// Cost of splitting a node of N triangles and surface area SA at a plane:
//   traversalCost + intersectionCost * (1 - bonus) * (SA_L/SA * N_L + SA_R/SA * N_R)
// (bonus = emptyBonus when a side is empty, else 0) against
// intersectionCost * N for a leaf. A triangle goes to a child iff its
// clipped bounds overlap the child's CLOSED voxel: triangles touching or
// lying in the plane go to both sides, which is what lets a traversal that
// rounds a crossing point to the wrong side still find them.
//
// Each node sorts its candidates per axis afresh, with a linear radix sort
// above 512 triangles (std::sort below), so a balanced build costs
// O(N log N) like the Wald–Havran presorted sweep without its bookkeeping
// (re-sorting and merging the events of clipped straddlers). Only triangles
// straddling a split are clipped again for the children, since the others'
// clipped bounds do not change. The node loop, clipping and the parallel
// build are kd_build_driver.h's, shared with the binned builder
// (kd_binned_builder.h); this file holds the exact plane search.
// A 100,000-triangle soup builds in about 0.65 s of CPU time (one EPYC core).

#include <cstddef>
#include <span>

#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"

namespace passtrace {

struct KdBuildConfig {
  int maxDepth = 0;             // splits on any root-to-leaf path (so depth() <= maxDepth + 1);
                                // 0 = kdDefaultMaxDepth(N); capped at kKdDepthLimit
  int minElements = 2;          // tracy -e: a node with this many triangles or fewer becomes a leaf
  float traversalCost = 1.0f;   // cost of one internal node step, relative to...
  float intersectionCost = 1.5f;  // ...one ray/triangle test
  float emptyBonus = 0.0f;      // in [0, 1): discount for splits that cut off empty space
  bool splitClipping = true;    // clip triangles to the voxel for candidates (Havran); false:
                                // use the triangles' bounds (cut to the voxel)
  // No voxel thinner than this fraction of the scene's diagonal: the
  // stackless GPU traversals (kd-restart, kd-backtrack) step from leaf to
  // leaf by t alone, and a voxel whose t-interval rounds to a single float
  // is never entered (BART Kitchen has planes 1.8e-7 apart). 0 disables it.
  float minVoxelFraction = 1e-4f;
};

// pbrt's and the thesis's maximum depth, 8 + 1.3 log2 N rounded (pbrt floors
// log2 N first; we do not). 8 for N <= 1.
int kdDefaultMaxDepth(size_t triangleCount);

// The depth a config asks for on N triangles: maxDepth, or the default when
// 0, clamped to [0, kKdDepthLimit].
int kdEffectiveMaxDepth(const KdBuildConfig& config, size_t triangleCount);

// An empty scene gives an empty tree. Triangles may be degenerate, flat,
// duplicated or all in one point; no triangle is ever dropped (a triangle
// that touches a leaf's voxel is in its list).
KdTree buildKdTree(std::span<const Triangle> tris, const KdBuildConfig& config = {});

}  // namespace passtrace
