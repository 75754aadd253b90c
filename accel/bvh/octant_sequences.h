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
// The eight sequences have the same size (the same tree, reordered), so
// they lie back to back and a ray reads sequence o at o * size. Their boxes
// are quantized to one grid over the root's box (octantBoxGrid), a texel each
// (eight copies of full-precision boxes were 256 of the stream path's 607
// bytes per triangle), and their leaves are one texel over a triangle stream
// the eight share (LeafTexels::Shared). The CPU row walks the same texels.

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

// Octant 0's sequence (shared leaves, quantized boxes; slots number the
// leaves in this sequence's order) and the triangle stream the eight share:
// everything the eight sequences are made of, so the tree can go before
// they are written. The stream path's peak was the tree (96 bytes per
// triangle) beside the eight sequences' texture.
struct OctantZero {
  EscapeSequence sequence;
  std::vector<glm::vec4> triangles;  // sharedTriangleTexels, in sequence 0's leaf order
  std::vector<uint32_t> slotTriangles;  // each slot's scene triangle: what writing needs once `triangles` is uploaded
};

// The eight sequences back to back and the triangle stream: the stream
// path's layout, kept whole (the CPU row; tests).
struct OctantSequences {
  std::vector<glm::vec4> texels;
  uint64_t sequenceTexels = 0;  // each sequence's
  BoxGrid grid;
  std::vector<glm::vec4> triangles;
  SequenceView sequence(uint32_t octant) const {
    return {std::span(texels).subspan(octant * sequenceTexels, sequenceTexels), &grid, triangles};
  }
};

// A binary BVH of the stack-BVH builders (accel/bvh_stack/) as a Bvh: a leaf of
// k > 1 references becomes an internal node over k one-triangle leaves (its
// box, then its triangles in the sequence), a leaf of one reference a leaf.
Bvh bvhFromBinaryBvh(const BinaryBvh& binary, std::span<const Triangle> tris);

// The grid every sequence of `bvh` quantizes its boxes to: over the root's box.
BoxGrid octantBoxGrid(const Bvh& bvh);
inline constexpr uint64_t kOctantBoxTexels = 1;

// Children of each internal node sorted by their quantized boxes' centres
// (in grid units, exact) along the octant's diagonal (+-1, +-1, +-1), nearest
// first; ties keep stored order. Sequence o is octant 0's tree ordered for o.
Bvh orderChildrenForOctant(const Bvh& bvh, uint32_t octant, const BoxGrid& grid);
OctantZero flattenOctantZero(const Bvh& bvh, std::span<const Triangle> tris);

// The eight sequences from octant zero, in pieces of at most
// kOctantWriteTexels handed to `write` (first texel, texels), octant by
// octant: each re-walks sequence 0, ordering a box's children for its octant
// (their keys read from their texels, a leaf's from its triangle's box:
// `tris` through zero.slotTriangles; zero.triangles is not read).
// Sequence o equals flattenEscapeSequence(orderChildrenForOctant(octant 0's
// tree, o, grid), tris, LeafTexels::Shared, its slots, &grid) texel for
// texel. 288 bytes per triangle in all with the triangle stream (416 with
// full-precision boxes, 640 with every sequence holding its triangles).
inline constexpr size_t kOctantWriteTexels = size_t(1) << 16;
void writeOctantSequences(const OctantZero& zero, std::span<const Triangle> tris,
                          const std::function<void(uint64_t first, std::span<const glm::vec4> texels)>& write);
// The same kept in memory.
OctantSequences octantSequencesFrom(OctantZero zero, std::span<const Triangle> tris);
OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris);

}  // namespace passtrace
