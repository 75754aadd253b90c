// Addressing shared with stream/texel_address.h: 1-D arrays in 2-D textures
// of power-of-two width, and indices carried in float channels.

// IEEE +infinity: the t of a ray that hit nothing.
const float INF = uintBitsToFloat(0x7F800000u);

ivec2 texelOf(uint index, uint widthLog2) {
  return ivec2(index & ((1u << widthLog2) - 1u), index >> widthLog2);
}

// A ConstInputStream (stream/const_input_stream.h): texels split into pages
// of 2^pageLog2, each page a texture of width 2^widthLog2. The C++ side
// compiles each kernel with STREAM_PAGES = the most pages any of its streams
// has; with 1 a fetch is one texelFetch, as in the thesis.
#ifndef STREAM_PAGES
#define STREAM_PAGES 1
#endif

struct ConstStream {
  sampler2D pages[STREAM_PAGES];
  uint widthLog2;
  uint pageLog2;
};

vec4 fetchTexel(ConstStream data, uint index) {
#if STREAM_PAGES == 1
  return texelFetch(data.pages[0], texelOf(index, data.widthLog2), 0);
#else
  // Sampler arrays may only be indexed by dynamically uniform expressions,
  // and rays differ in the page they read: select the page with constants.
  ivec2 at = texelOf(index & ((1u << data.pageLog2) - 1u), data.widthLog2);
  uint page = index >> data.pageLog2;
  if (page == 0u) return texelFetch(data.pages[0], at, 0);
  if (page == 1u) return texelFetch(data.pages[1], at, 0);
#if STREAM_PAGES > 2
  if (page == 2u) return texelFetch(data.pages[2], at, 0);
#endif
#if STREAM_PAGES > 3
  if (page == 3u) return texelFetch(data.pages[3], at, 0);
#endif
#if STREAM_PAGES > 4
  if (page == 4u) return texelFetch(data.pages[4], at, 0);
#endif
#if STREAM_PAGES > 5
  if (page == 5u) return texelFetch(data.pages[5], at, 0);
#endif
#if STREAM_PAGES > 6
  if (page == 6u) return texelFetch(data.pages[6], at, 0);
#endif
#if STREAM_PAGES > 7
  if (page == 7u) return texelFetch(data.pages[7], at, 0);
#endif
  return vec4(0.0);  // beyond the data: callers never ask
#endif
}

// One float of a scalar array stored four to a texel (reference lists, grid cells).
float fetchScalar(ConstStream data, uint index) {
  return fetchTexel(data, index >> 2u)[index & 3u];
}

// Raw bits offset by 2^23: never denormal, exact beyond 2^24.
float packIndex(uint index) { return uintBitsToFloat(index + 0x00800000u); }
uint unpackIndex(float bits) { return floatBitsToUint(bits) - 0x00800000u; }

// This fragment's own element of a stream surface (the only texel a kernel
// may read from a surface it also writes).
vec4 readElement(sampler2D surface) { return texelFetch(surface, ivec2(gl_FragCoord.xy), 0); }
