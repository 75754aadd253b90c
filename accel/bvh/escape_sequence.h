#pragma once
// The escape-index sequence (thesis 9.4, "partial evaluation" of the
// recursive descent): the tree flattened depth first into RGBA texels, each
// box carrying the index where traversal resumes when the ray misses it.
// The GLSL kernel reads exactly this layout:
//
//   box (internal node), 2 texels:
//     [i]   (min.x, min.y, min.z, packIndex(escape))
//     [i+1] (max.x, max.y, max.z, 0)
//   triangle (leaf), 3 texels:
//     [i]   (v0.x, v0.y, v0.z, -1)   negative w marks a triangle
//     [i+1] (v1.x, v1.y, v1.z, packIndex(scene triangle index))
//     [i+2] (v2.x, v2.y, v2.z, 0)
//
// escape is the texel index just after the box's subtree, texels.size() for
// boxes on the right edge of the tree; a triangle's escape is implicitly i+3.
//
// With LeafTexels::Shared (bvh-octant on the stream path, whose eight
// sequences would otherwise store every triangle eight times) a triangle is
// one texel, its escape i+1:
//     [i]   (v0.x, v0.y, v0.z, -packIndex(slot))
// and texels 2 slot and 2 slot + 1 of a triangle stream the sequences share
// (sharedTriangleTexels) hold (v1, packIndex(scene triangle index)) and
// (v2, 0). Slots number the leaves depth first in the tree's stored order
// (leafSlots), so a subtree's triangles lie together in the stream whichever
// order a sequence walks it in (scene order cost bvh-octant-fused 8-14 % on
// the bunny). packIndex is never 0, so w < 0 still marks a triangle.
// Packed indices are positive floats (stream/texel_address.h), so w >= 0
// tells a box from a triangle with the first read.
//
// With a BoxGrid (bvh-octant, whose eight sequences copy every box) a box is
// one texel, its planes quantized outwards (accel/bvh/box_grid.h):
//     [i]   (grid planes x, y, z, packIndex(escape))

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/box_grid.h"
#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"
#include "stream/texel_address.h"

namespace passtrace {

// What a walk reads (accel/bvh/bvh_traversal.h): the texels; with a grid,
// boxes of one quantized texel; with shared triangles, leaves of one texel
// over them (LeafTexels::Shared).
struct SequenceView {
  std::span<const glm::vec4> texels;
  const BoxGrid* grid = nullptr;
  std::span<const glm::vec4> sharedTriangles;
};

struct EscapeSequence {
  std::vector<glm::vec4> texels;
  uint32_t boxCount = 0;       // internal nodes
  uint32_t triangleCount = 0;  // leaves
  std::optional<BoxGrid> grid; // set: boxes of one quantized texel

  // Leaves inline (a LeafTexels::Shared sequence needs its triangle stream beside it).
  operator SequenceView() const { return {texels, grid ? &*grid : nullptr, {}}; }

  // Memory overhead as the thesis counts it (Table 3): 8 floats per box (4
  // quantized), triangles excluded as every structure stores them. A binary
  // tree with one triangle per leaf has N - 1 boxes, giving 8 (N - 1) / N.
  float floatsPerTriangle() const {
    const float perBox = grid ? 4.0f : 8.0f;
    return triangleCount == 0 ? 0.0f : perBox * static_cast<float>(boxCount) / static_cast<float>(triangleCount);
  }
};

enum class LeafTexels { Inline, Shared };
inline constexpr uint64_t kBoxTexels = 2;  // full precision; one with a BoxGrid
inline constexpr uint64_t boxTexelCount(const BoxGrid* grid) { return grid ? 1 : kBoxTexels; }
inline constexpr uint64_t leafTexelCount(LeafTexels leaves) { return leaves == LeafTexels::Inline ? 3 : 1; }
// packIndex is valid below this; a sequence's texel indices must stay under it.
inline constexpr uint64_t kMaxSequenceTexels = 0x7F000000u;

// Depth first, children in stored order. Throws std::invalid_argument for a
// leaf whose triangle index is outside tris, std::length_error when the
// sequence would exceed the packable index range.
// LeafTexels::Shared takes the slots (leafSlots) of the tree the stream was
// made from; empty: `bvh`'s own. With `grid`, boxes are quantized to it.
EscapeSequence flattenEscapeSequence(const Bvh& bvh, std::span<const Triangle> tris,
                                     LeafTexels leaves = LeafTexels::Inline, std::span<const uint32_t> slots = {},
                                     const BoxGrid* grid = nullptr);

// The texels of a box (boxTexelCount(grid) of them) and of a leaf in either layout.
inline void writeBoxTexels(glm::vec4* out, const Aabb& box, uint32_t escape, const BoxGrid* grid = nullptr) {
  if (grid) {
    out[0] = glm::vec4(grid->encode(box), packIndex(escape));
    return;
  }
  out[0] = glm::vec4(box.min, packIndex(escape));
  out[1] = glm::vec4(box.max, 0.0f);
}
// `slot`: LeafTexels::Shared's, ignored by Inline.
void writeLeafTexels(glm::vec4* out, const Triangle& tri, uint32_t triangle, uint32_t slot, LeafTexels leaves);

// Per node: a leaf's rank among the leaves in depth-first stored order (kNoHit for inner nodes).
std::vector<uint32_t> leafSlots(const Bvh& bvh);
// LeafTexels::Shared's triangle stream: (v1, packIndex(triangle)), (v2, 0) per leaf, in slot order
// (`slots` as leafSlots(bvh) gives them; empty: computed here).
std::vector<glm::vec4> sharedTriangleTexels(const Bvh& bvh, std::span<const Triangle> tris,
                                            std::span<const uint32_t> slots = {});

}  // namespace passtrace
