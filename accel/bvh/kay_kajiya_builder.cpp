#include "accel/bvh/kay_kajiya_builder.h"

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <vector>

namespace passtrace {
namespace {

// What the builder reads of a triangle, stored contiguously and partitioned
// in place: every level streams through memory instead of gathering triangles
// by index (a 5x difference at millions of triangles).
struct Ref {
  Aabb bounds;
  glm::vec3 centroid;
  uint32_t index;
};

// A pending node: its triangles are refs[begin, end), and centroidBox bounds
// their centroids (the node's own box is already stored in the node).
struct PendingRange {
  uint32_t node;
  uint32_t begin, end;
  Aabb centroidBox;
};

// Uniform in [0, 1) from the top 53 bits: spelled out rather than
// std::uniform_real_distribution, whose output differs between standard
// libraries, so a seed names the same tree everywhere.
double unitInterval(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

Bvh buildKayKajiya(std::span<const Triangle> tris, const KayKajiyaConfig& config) {
  Bvh bvh;
  const size_t count = tris.size();
  if (count == 0) return bvh;
  if (count >= kNoHit) throw std::length_error("buildKayKajiya: too many triangles for 32-bit indices");
  const auto n = static_cast<uint32_t>(count);

  std::vector<Ref> refs(n);
  Aabb rootBox, rootCentroids;
  for (uint32_t i = 0; i < n; ++i) {
    refs[i] = Ref{tris[i].bounds(), tris[i].centroid(), i};
    rootBox.extend(refs[i].bounds);
    rootCentroids.extend(refs[i].centroid);
  }

  bvh.nodes.reserve(2 * size_t{n} - 1);
  bvh.children.reserve(2 * size_t{n} - 2);
  bvh.nodes.push_back(BvhNode{rootBox});

  std::mt19937_64 rng(config.seed);
  std::vector<PendingRange> stack{{0, 0, n, rootCentroids}};  // depth-first: holds at most depth + 1 items
  while (!stack.empty()) {
    const PendingRange work = stack.back();
    stack.pop_back();
    const uint32_t size = work.end - work.begin;
    if (size == 1) {
      bvh.nodes[work.node].triangle = refs[work.begin].index;
      continue;
    }

    // Try the spatial median of the centroid box on all three axes at once.
    const glm::vec3 median = work.centroidBox.center();
    std::array<Aabb, 3> leftBox, rightBox;
    std::array<uint32_t, 3> leftCount{0, 0, 0};
    for (uint32_t i = work.begin; i < work.end; ++i) {
      const Ref& r = refs[i];
      for (int axis = 0; axis < 3; ++axis) {
        if (r.centroid[axis] < median[axis]) {
          leftBox[axis].extend(r.bounds);
          ++leftCount[axis];
        } else {
          rightBox[axis].extend(r.bounds);
        }
      }
    }
    int best = -1;
    float bestArea = 0.0f;
    for (int axis = 0; axis < 3; ++axis) {
      if (leftCount[axis] == 0 || leftCount[axis] == size) continue;  // no split on this axis
      const float area = leftBox[axis].surfaceArea() + rightBox[axis].surfaceArea();
      if (best < 0 || area < bestArea) {  // ties keep the lower axis
        best = axis;
        bestArea = area;
      }
    }

    // The halves are sets: their order inside refs does not affect the tree
    // (boxes are min/max, the fallback orders by index), so the unstable
    // in-place partitions below still give the same tree on any library.
    const auto first = refs.begin() + work.begin, last = refs.begin() + work.end;
    uint32_t mid;
    Aabb childBox[2], childCentroids[2];
    if (best >= 0) {
      const float m = median[best];
      mid = static_cast<uint32_t>(std::partition(first, last, [&](const Ref& r) { return r.centroid[best] < m; }) -
                                  refs.begin());
      childBox[0] = leftBox[best];
      childBox[1] = rightBox[best];
    } else {
      // Coincident centroids (or NaNs): no axis separates them. Halve in
      // scene order: the lower half of the indices goes left.
      mid = work.begin + size / 2;
      std::nth_element(first, refs.begin() + mid, last, [](const Ref& a, const Ref& b) { return a.index < b.index; });
    }
    for (uint32_t i = work.begin; i < work.end; ++i) {
      const int side = i < mid ? 0 : 1;
      if (best < 0) childBox[side].extend(refs[i].bounds);
      childCentroids[side].extend(refs[i].centroid);
    }

    const auto left = static_cast<uint32_t>(bvh.nodes.size());
    const uint32_t right = left + 1;
    bvh.nodes.push_back(BvhNode{childBox[0]});
    bvh.nodes.push_back(BvhNode{childBox[1]});
    // One draw per internal node, always, so the tree shape for a seed does
    // not depend on the probability.
    const bool swap = unitInterval(rng) < static_cast<double>(config.swapProbability);
    BvhNode& node = bvh.nodes[work.node];
    node.firstChild = static_cast<uint32_t>(bvh.children.size());
    node.childCount = 2;
    bvh.children.push_back(swap ? right : left);
    bvh.children.push_back(swap ? left : right);

    // Right pushed first so the left subtree is built first.
    stack.push_back({right, mid, work.end, childCentroids[1]});
    stack.push_back({left, work.begin, mid, childCentroids[0]});
  }
  return bvh;
}

}  // namespace passtrace
