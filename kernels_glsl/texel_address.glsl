// Addressing shared with stream/texel_address.h: 1-D arrays in 2-D textures
// of power-of-two width, and indices carried in float channels.

// IEEE +infinity: the t of a ray that hit nothing.
const float INF = uintBitsToFloat(0x7F800000u);

ivec2 texelOf(uint index, uint widthLog2) {
  return ivec2(index & ((1u << widthLog2) - 1u), index >> widthLog2);
}

uint widthLog2Of(sampler2D data) { return uint(findMSB(textureSize(data, 0).x)); }

vec4 fetchTexel(sampler2D data, uint widthLog2, uint index) {
  return texelFetch(data, texelOf(index, widthLog2), 0);
}

// One float of a scalar array stored four to a texel (reference lists, grid cells).
float fetchScalar(sampler2D data, uint widthLog2, uint index) {
  return fetchTexel(data, widthLog2, index >> 2u)[index & 3u];
}

// Raw bits offset by 2^23: never denormal, exact beyond 2^24.
float packIndex(uint index) { return uintBitsToFloat(index + 0x00800000u); }
uint unpackIndex(float bits) { return floatBitsToUint(bits) - 0x00800000u; }

// This fragment's own element of a stream surface (the only texel a kernel
// may read from a surface it also writes).
vec4 readElement(sampler2D surface) { return texelFetch(surface, ivec2(gl_FragCoord.xy), 0); }
