#pragma once
// The compact 8-byte kd node of seed 002's standard stack traversal: two
// floats, so two nodes share one RGBA32F texel (node i at texel i / 2, in .xy
// when i is even, .zw when odd). Word 0 is the split position (0 in a leaf);
// word 1 is packIndex(payload << 2 | code), code 0-2 = the split axis with
// payload = the right child's node index (the left child is the next node),
// code 3 = a leaf with payload = its first list entry + 1, or 0 when empty.
// packIndex keeps the word a normal positive float (stream/texel_address.h), so
// payloads up to 2^29 - 1 fit. The restart layout (kd_texels.h) spends 16 bytes.

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "stream/texel_address.h"

namespace passtrace {

inline constexpr uint32_t kKdCompactLeafCode = 3;
inline constexpr uint32_t kKdCompactMaxPayload = (1u << 29) - 1;

inline glm::vec2 encodeKdCompactNode(float split, uint32_t code, uint32_t payload) {
  return {split, packIndex(payload << 2 | code)};
}

// Node `node` of compact texels in the restart layout's texel form (kd_texels.h),
// parent -1 (the stack traversal never reads it).
inline glm::vec4 kdCompactNodeTexel(std::span<const glm::vec4> texels, uint32_t node) {
  const glm::vec4 pair = texels[node >> 1];
  const glm::vec2 n = (node & 1u) ? glm::vec2(pair.z, pair.w) : glm::vec2(pair.x, pair.y);
  const uint32_t word = unpackIndex(n.y);
  const uint32_t code = word & 3u, payload = word >> 2;
  if (code == kKdCompactLeafCode) return {0.0f, 0.0f, -1.0f, payload == 0 ? -1.0f : packIndex(payload - 1)};
  return {packIndex(payload), n.x, -1.0f, -(static_cast<float>(code) + 2.0f)};
}

}  // namespace passtrace
