#pragma once
// The index-to-texel mapping shared by C++ and GLSL (kernels_glsl/texel_address.glsl):
// a 1-D array of RGBA texels lives row by row in a 2-D texture whose width is
// a power of two, so the mapping is a mask and a shift.

#include <bit>
#include <cstdint>

namespace passtrace {

struct TexelCoord {
  uint32_t x, y;
};

inline TexelCoord texelOf(uint32_t index, uint32_t widthLog2) {
  return {index & ((1u << widthLog2) - 1u), index >> widthLog2};
}

// Indices travel in float channels as raw bits offset by 2^23, so they are never
// denormal (GPUs may flush denormals to zero) and stay exact beyond 2^24.
// Packed indices are positive floats; valid for index < 0x7F000000.
inline float packIndex(uint32_t index) { return std::bit_cast<float>(index + 0x00800000u); }
inline uint32_t unpackIndex(float packed) { return std::bit_cast<uint32_t>(packed) - 0x00800000u; }

// A uint's raw bits in a float, for data the kernels read back with
// floatBitsToUint (the cone kernels' buffers: never sampled nor filtered).
inline float bitsAsFloat(uint32_t u) { return std::bit_cast<float>(u); }

}  // namespace passtrace
