#pragma once
// A kd-tree built the pbrt way (Pharr & Humphreys, pbrt-v3 KdTreeAccel;
// thesis Table 4, CPU accelerator 3 "Kd-tree (pbrt)"), into the same KdTree
// form as the SAH builder, so one traversal serves both.
//
// What makes it pbrt's rather than kd_tree_builder.h's:
//  - candidates at the faces of each triangle's FULL bounds (no split
//    clipping), strictly inside the voxel, on one axis at a time: the
//    voxel's longest, then the next two only if that one has no candidate;
//  - pbrt's edge order (by position, starts before ends at a tie) and its
//    classification: triangles whose start edge sorts before the chosen edge
//    go below, those whose end edge sorts after it go above (so a triangle
//    merely touching the plane goes to one side only);
//  - pbrt's cost, traversal + isect * (1 - bonus) * (P_below N_below +
//    P_above N_above), the bonus applying when one side is empty;
//  - badRefines: a split costlier than a leaf is still taken, but the third
//    such on a root-to-leaf path makes a leaf, as does a split costing more
//    than four leaves on fewer than 16 triangles.
// The leaf lists are sorted by triangle index (pbrt keeps edge order), so
// among triangles hit at the same t in one leaf the lowest index wins.

#include <span>

#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/kd_tree_builder.h"

namespace passtrace {

// pbrt-v3's defaults: isectCost 80, traversalCost 1, emptyBonus 0.5,
// maxPrims 1, maxDepth 8 + 1.3 log2 N (kdDefaultMaxDepth). splitClipping
// is ignored by buildKdTreePbrt.
inline constexpr KdBuildConfig kPbrtKdConfig{.maxDepth = 0,
                                             .minElements = 1,
                                             .traversalCost = 1.0f,
                                             .intersectionCost = 80.0f,
                                             .emptyBonus = 0.5f,
                                             .splitClipping = false};

// config.minElements plays pbrt's maxPrims (a node with that many triangles
// or fewer is a leaf); maxDepth counts splits as pbrt's depth does. An empty
// scene gives an empty tree.
KdTree buildKdTreePbrt(std::span<const Triangle> tris, const KdBuildConfig& config = kPbrtKdConfig);

}  // namespace passtrace
