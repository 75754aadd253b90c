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
// GPU stores them back to back and a ray reads sequence o at o * size.

#include <array>
#include <cstdint>
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
OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris);

// The same eight sequences back to back, as the GPU reads them: flattened one
// octant at a time into one array, so that the eight apart and their
// concatenation never coexist (the stream path's peak memory: 1,936 bytes per
// triangle held the eight, the concatenation and the texture at once).
struct BackToBackSequences {
  std::vector<glm::vec4> texels;
  uint64_t sequenceSize = 0;  // texels in one sequence
  float floatsPerTriangle = 0;  // one sequence's (EscapeSequence::floatsPerTriangle)
};
BackToBackSequences flattenOctantSequencesBackToBack(const Bvh& bvh, std::span<const Triangle> tris);

}  // namespace passtrace
