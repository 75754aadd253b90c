#pragma once
// Where the compute stage keeps a stream's elements (stream/inout_stream.h).
// Its surfaces are buffers in tile order: element (x, y) is at slot
// tile * 64 + lane, where tile = (y / 8) * tilesPerRow + x / 8 and lane is
// the invocation of that tile's work group that runs the element
// (stream/compute_variant.cpp: each run of 8 lanes a 4x2 block, each run of
// 32 an 8x4 block). A dispatch over every element then stores each SIMD
// vector's lanes to consecutive slots: llvmpipe stores a vector lane by lane,
// and only consecutive addresses fold into a short loop (images at the
// pixel cost the compute stage 1.4-1.5x the fragment stage's frame,
// docs/bench-speed/NOTES.md). The GLSL twin is slotOf_ in compute_variant.cpp.

#include <cstdint>

namespace passtrace {

constexpr uint32_t kSlotTileSide = 8;
constexpr uint32_t kSlotsPerTile = kSlotTileSide * kSlotTileSide;

// The lane of (x, y) within its 8x8 tile: x bits 0-1 and 2 go to lane bits
// 0-1 and 3, y bit 0 to lane bit 2, y bits 1-2 to lane bits 4-5.
inline uint32_t tileLane(uint32_t x, uint32_t y) {
  return (x & 3u) | ((y & 1u) << 2u) | ((x & 4u) << 1u) | ((y & 6u) << 3u);
}

// Tiles along a side of n elements.
inline uint32_t tilesAlong(uint32_t n) { return (n + kSlotTileSide - 1) / kSlotTileSide; }

inline uint64_t elementSlot(uint32_t x, uint32_t y, uint32_t width) {
  const uint64_t tile = uint64_t(y / kSlotTileSide) * tilesAlong(width) + x / kSlotTileSide;
  return tile * kSlotsPerTile + tileLane(x % kSlotTileSide, y % kSlotTileSide);
}

// Slots a width x height surface takes: whole tiles.
inline uint64_t surfaceSlots(uint32_t width, uint32_t height) {
  return uint64_t(tilesAlong(width)) * tilesAlong(height) * kSlotsPerTile;
}

}  // namespace passtrace
