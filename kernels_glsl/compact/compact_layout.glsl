// Live-ray compaction (stream/stream_compaction.h): where the compact stream
// keeps live ray number `slot`. Sixteen consecutive slots fill one 4x4 block
// (llvmpipe's unit of early depth culling), blocks fill rows of
// uBlocksPerRow, so the live rays are one dense run of whole blocks.

uniform uint uBlocksPerRow;

ivec2 compactTexel(uint slot) {
  uint block = slot >> 4u, inBlock = slot & 15u;
  return ivec2((block % uBlocksPerRow) * 4u + (inBlock & 3u), (block / uBlocksPerRow) * 4u + (inBlock >> 2u));
}

uint compactSlot(ivec2 texel) {
  uint block = uint(texel.y >> 2) * uBlocksPerRow + uint(texel.x >> 2);
  return block * 16u + uint(texel.y & 3) * 4u + uint(texel.x & 3);
}

// Element k of the ray stream's row-major order and back.
uniform uint uHomeWidth;
uint homeIndex(ivec2 texel) { return uint(texel.y) * uHomeWidth + uint(texel.x); }
ivec2 homeTexel(uint index) { return ivec2(index % uHomeWidth, index / uHomeWidth); }

// slots[0] counts the live rays; homes[slot] is the element a slot came from,
// slotOf[element] the slot an element went to.
layout(std430, binding = 0) buffer CompactHomes { uint liveCount; uint homes[]; };
layout(std430, binding = 1) buffer CompactSlots { uint slotOf[]; };

// The copied surfaces: SURFACES of them, at most 8 (InOutStream::kMaxSurfaces).
#ifndef SURFACES
#define SURFACES 8
#endif
