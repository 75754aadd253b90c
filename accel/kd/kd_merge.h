#pragma once
// Merging a dynamic object's kd-tree into a static scene's kd-tree (seed 003
// ch. 10, Algorithms 9-12), for --dynamic merge: each frame the dynamic tree
// is built over the moving triangles, merged into the static tree built once,
// and the merged tree is traced.
//
// The partition of a tree by a plane (the seed's Algorithm 9, lost in the
// extraction) is done lazily here: a subtree is never copied to be split;
// instead each side carries the subtree's root with a clip box (the region
// it may still cover). Partitioning by the plane (axis, p) clips that box at
// p on both sides. On the way down, a node of either tree whose plane does
// not cut the clip box strictly is skipped for the one child that covers the
// box (the node "lies on one side"); a node whose plane cuts it is kept and
// becomes an internal node of the merged tree (it "straddles"), its voxel the
// clip box. A leaf reached by both trees lists both leaves' references
// (straddling references are thus duplicated), less those whose bounds miss
// the clip box.
//
// The merge walks the static tree first (the dynamic tree is pushed down the
// static planes to the static leaves it overlaps, Algorithms 10-11), then,
// inside each static leaf it reached, cuts off the empty space around the
// dynamic tree's bounds with up to six planes, then follows the dynamic
// tree's planes: the static leaf is replaced by the dynamic part with the
// static leaf's triangles added to its leaves. Static subtrees the dynamic
// tree does not reach are copied unchanged.
//
// Restoring the static tree (Algorithm 12): the layout is depth-first with
// the left child implicit (index + 1), so a leaf cannot be replaced in place
// by a subtree without moving everything after it. The merge therefore
// writes the merged tree into a buffer of its own in one depth-first pass
// and never writes the static tree: restoring it is dropping the merged
// buffer, and the static tree is reused unchanged next frame.
//
// The merged tree is a valid KdTree (tests/kd_checks): depth-first, parents,
// voxels splitting their parent's exactly, at most kKdDepthLimit levels (at
// the limit a node becomes a leaf listing every triangle below it), its root
// voxel the union of both trees' bounds. Reference ids are kept as they are:
// build both trees with global scene ids (buildKdTreeOver).

#include <span>

#include "accel/geometry/geometry.h"
#include "accel/kd/kd_tree.h"

namespace passtrace {

// `tris` is the frame's scene (both trees' references index it). Either tree
// may be empty.
KdTree mergeKdTrees(const KdTree& staticTree, const KdTree& dynamicTree, std::span<const Triangle> tris);

}  // namespace passtrace
