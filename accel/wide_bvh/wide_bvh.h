#pragma once
// An 8-wide BVH collapsed from a binary SAH BVH (binary_bvh.h; or an SBVH's,
// sbvh_binary_bvh.h, whose leaves may share triangles). Nodes are
// SoA: the eight child boxes as eight lanes of min/max per axis, so one AVX2
// instruction tests a slab of all eight. Leaves hold their triangles in SoA
// packs of four (vertex 0 and the two edges, Möller–Trumbore's inputs) so the
// triangle test runs four lanes at once. Unused child lanes hold the box
// [+inf, +inf], which every ray misses, so the traversal needs no lane count.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/wide_bvh/binary_bvh.h"

namespace passtrace {

inline constexpr int kWideBvhWidth = 8;
inline constexpr int kTrianglePackWidth = 4;

// A child reference: an inner node's index, or with kWideLeafBit a leaf of
// ((ref >> 29) & 3) + 1 consecutive packs starting at pack (ref & kWideLeafFirstMask).
inline constexpr uint32_t kWideLeafBit = 0x80000000u;
inline constexpr uint32_t kWideLeafFirstMask = 0x1FFFFFFFu;
inline constexpr uint32_t kWideEmpty = 0xFFFFFFFFu;  // an unused lane
inline constexpr uint32_t kWideMaxLeafPacks = 4;

inline bool wideIsLeaf(uint32_t ref) { return (ref & kWideLeafBit) != 0; }
inline uint32_t wideLeafFirst(uint32_t ref) { return ref & kWideLeafFirstMask; }
inline uint32_t wideLeafPacks(uint32_t ref) { return ((ref >> 29) & 3u) + 1u; }

struct alignas(32) WideBvhNode {
  float minX[8], maxX[8], minY[8], maxY[8], minZ[8], maxZ[8];
  uint32_t child[8];
};

// Unused lanes: v0 = e1 = e2 = 0 (determinant 0: never hit) and id kNoHit.
struct alignas(16) TrianglePack {
  float v0x[4], v0y[4], v0z[4];
  float e1x[4], e1y[4], e1z[4];
  float e2x[4], e2y[4], e2z[4];
  uint32_t id[4];
  uint32_t count() const {
    uint32_t c = 0;
    for (uint32_t i : id) c += i != kNoHit;
    return c;
  }
};

struct WideBvh {
  std::vector<WideBvhNode> nodes;  // nodes[0] is the root (absent when there are no triangles)
  std::vector<TrianglePack> packs;
  uint32_t depth = 0;              // wide levels, leaves included
  uint32_t leaves = 0;
  uint32_t references = 0;         // triangles stored (once per leaf; an SBVH's in several leaves)
  // Entries a traversal stack can need: up to 7 siblings per level.
  uint32_t stackSize() const { return 7 * depth + 8; }
  size_t bytes() const { return nodes.size() * sizeof(WideBvhNode) + packs.size() * sizeof(TrianglePack); }
};

struct WideBvhConfig {
  // Binary subtrees of at most this many triangles become one leaf (one pack).
  uint32_t mergeLeafTriangles = kTrianglePackWidth;
};

// Greedy collapse: a wide node adopts its binary node's two children, then
// keeps opening the inner child of largest surface area until it has eight.
WideBvh collapseToWideBvh(const SahBinaryBvh& bvh, std::span<const Triangle> tris, const WideBvhConfig& config = {});

}  // namespace passtrace
