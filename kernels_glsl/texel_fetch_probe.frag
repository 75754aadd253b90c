// What one texel fetch costs on this driver, for the stream path's roofline
// (tests/measure/texel_fetch.cpp). Each element reads uFetches texels of a
// table whose texel i names i + 1 in w, as a walk's texel names the next one:
// with uDependent the address comes from the texel before (the walk's chain),
// without it the same addresses are computed from the start alone. Elements of
// one uTile x uTile block start at the same texel (coherent rays reading the
// same nodes); uTile 1 gives every element its own start.
#include "texel_address.glsl"

uniform ConstStream uTable;
uniform uint uTableSize;
uniform int uFetches;
uniform bool uDependent;
uniform uint uTile;

layout(location = 0) out vec4 outSum;

// A start that spreads the blocks over the table (a 32-bit integer hash),
// early enough that no element reads past the table's end: the addresses
// then need no wrapping, whose integer division would cost more than a fetch.
uint startOf(uvec2 block) {
  uint h = block.x * 0x9E3779B1u ^ block.y * 0x85EBCA77u;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return h % (uTableSize - uint(uFetches));
}

void main() {
  uint start = startOf(uvec2(gl_FragCoord.xy) / uTile), index = start;
  vec4 sum = vec4(0.0);  // written out, so that no fetch is optimised away
  for (int i = 0; i < uFetches; ++i) {
    vec4 texel = fetchTexel(uTable, index);
    sum += texel;
    index = uDependent ? unpackIndex(texel.w) : start + uint(i) + 1u;
  }
  outSum = sum;
}
