#pragma once
// A BVH flattened eight times, once per ray octant (the signs of the
// direction's components), each time with every node's children in
// near-first order for that octant: a ray walks the escape-index sequence of
// its own octant (thesis 9.4's algorithm unchanged), so it meets the nearer
// subtree first and the hit found there culls the farther boxes, while its
// state between passes stays one index (texel-only, no per-ray stack).
// The idea is Hachisuka's multiple-threaded BVH (six orders by the dominant
// axis) with one order per octant instead.
//
// The eight sequences have the same size (the same tree, reordered), so the
// GPU stores them back to back and a ray reads sequence o at o * size. Their
// boxes are quantized to one grid over the root's box (octantBoxGrid), a texel
// each: eight copies of full-precision boxes were 256 of the stream path's 607
// bytes per triangle.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh_stack/binary_bvh.h"
#include "accel/geometry/geometry.h"

namespace passtrace {

inline constexpr uint32_t kOctants = 8;

// Bit 0, 1, 2 set when the direction's x, y, z is negative (-0 counts as
// positive); kernels_glsl/bvh/bvh_octant_traverse.frag computes the same.
inline uint32_t rayOctant(const glm::vec3& direction) {
  return (direction.x < 0.0f ? 1u : 0u) | (direction.y < 0.0f ? 2u : 0u) | (direction.z < 0.0f ? 4u : 0u);
}

struct OctantSequences {
  std::array<EscapeSequence, kOctants> sequences;  // by rayOctant
};

// A binary BVH of the stack-BVH builders (accel/bvh_stack/) as a Bvh: a leaf of
// k > 1 references becomes an internal node over k one-triangle leaves (its
// box, then its triangles in the sequence), a leaf of one reference a leaf.
Bvh bvhFromBinaryBvh(const BinaryBvh& binary, std::span<const Triangle> tris);

// Children of each internal node sorted by their box centres projected on the
// octant's diagonal (+-1, +-1, +-1), nearest first; ties keep stored order.
Bvh orderChildrenForOctant(const Bvh& bvh, uint32_t octant);
// The grid every sequence of `bvh` quantizes its boxes to: over the root's box.
BoxGrid octantBoxGrid(const Bvh& bvh);
inline constexpr uint64_t kOctantBoxTexels = 1;
// The CPU row's sequences: triangles inline (LeafTexels::Inline), quantized boxes.
OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris);

// The stream path's layout: the eight sequences back to back (sequence o at
// texel o * octantSequenceTexels), leaves of one texel over a triangle stream
// they share (LeafTexels::Shared, sharedTriangleTexels): eight copies of the
// boxes but one of the triangles, 288 bytes per triangle in all (416 with
// full-precision boxes, 640 with LeafTexels::Inline too). writeOctantSequences hands them to `write` in
// pieces of at most kOctantWriteTexels, walking the tree in each octant's
// order without copying it, so the only whole copy is the one `write` makes
// (the texture): before, the eight, their concatenation and the texture
// coexisted (1,936 bytes per triangle at the peak, then 1,313).
// Sequence o equals flattenEscapeSequence(orderChildrenForOctant(bvh, o),
// tris, LeafTexels::Shared, leafSlots(bvh), &octantBoxGrid(bvh)) texel for texel.
inline constexpr size_t kOctantWriteTexels = size_t(1) << 16;
uint64_t octantSequenceTexels(const Bvh& bvh);
void writeOctantSequences(const Bvh& bvh, std::span<const Triangle> tris,
                          const std::function<void(uint64_t first, std::span<const glm::vec4> texels)>& write);

}  // namespace passtrace
