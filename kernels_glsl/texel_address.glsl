// Addressing shared with stream/texel_address.h: 1-D arrays in 2-D textures
// of power-of-two width, and indices carried in float channels.

// IEEE +infinity: the t of a ray that hit nothing.
const float INF = uintBitsToFloat(0x7F800000u);

ivec2 texelOf(uint index, uint widthLog2) {
  return ivec2(index & ((1u << widthLog2) - 1u), index >> widthLog2);
}

// A ConstInputStream (stream/const_input_stream.h): texels split into pages
// of 2^pageLog2, each page a texture of width 2^widthLog2. A kernel reads
// its streams as ConstStream, compiled with STREAM_PAGES = the most pages any
// of them has; with 1 a fetch is one texelFetch, as in the thesis. Every page
// slot is a sampler and a stage has few (32 on llvmpipe), so a kernel whose
// one stream is far larger than the rest (bvh-octant's eight sequences)
// declares that one a LargeConstStream, with LARGE_STREAM_PAGES slots.
#ifndef STREAM_PAGES
#define STREAM_PAGES 1
#endif
#ifndef LARGE_STREAM_PAGES
#define LARGE_STREAM_PAGES STREAM_PAGES
#endif

// Declares the stream type `Type` with `PAGES` sampler slots and its fetches.
// Sampler arrays may only be indexed by dynamically uniform expressions, and
// rays differ in the page they read: the page is selected by comparing with
// each slot's constant index.
#define DECLARE_CONST_STREAM(Type, PAGES)                                        \
  struct Type {                                                                  \
    sampler2D pages[PAGES];                                                      \
    uint widthLog2;                                                              \
    uint pageLog2;                                                               \
  };                                                                             \
  vec4 fetchTexel(Type data, uint index) {                                       \
    if (PAGES == 1) return texelFetch(data.pages[0], texelOf(index, data.widthLog2), 0); \
    ivec2 at = texelOf(index & ((1u << data.pageLog2) - 1u), data.widthLog2);    \
    uint page = index >> data.pageLog2;                                          \
    for (int p = 0; p < PAGES; ++p)                                              \
      if (page == uint(p)) return texelFetch(data.pages[p], at, 0);              \
    return vec4(0.0); /* beyond the data: callers never ask */                   \
  }                                                                              \
  /* One float of a scalar array stored four to a texel (reference lists, grid cells). */ \
  float fetchScalar(Type data, uint index) { return fetchTexel(data, index >> 2u)[index & 3u]; }

DECLARE_CONST_STREAM(ConstStream, STREAM_PAGES)
DECLARE_CONST_STREAM(LargeConstStream, LARGE_STREAM_PAGES)

// Raw bits offset by 2^23: never denormal, exact beyond 2^24.
float packIndex(uint index) { return uintBitsToFloat(index + 0x00800000u); }
uint unpackIndex(float bits) { return floatBitsToUint(bits) - 0x00800000u; }

// This fragment's own element of a stream surface (the only texel a kernel
// may read from a surface it also writes), and the element at `texel` of a
// surface of a stream `width` elements wide. The compute stage keeps
// surfaces as buffers in tile order (stream/element_slots.h; its variant
// defines COMPUTE_STAGE, elementSlot_ and slotOf_).
#ifdef COMPUTE_STAGE
vec4 readElement(samplerBuffer surface) { return texelFetch(surface, int(elementSlot_)); }
vec4 readElementAt(samplerBuffer surface, ivec2 texel, uint width) {
  return texelFetch(surface, int(slotOf_(uvec2(texel), width)));
}
#else
vec4 readElement(sampler2D surface) { return texelFetch(surface, ivec2(gl_FragCoord.xy), 0); }
vec4 readElementAt(sampler2D surface, ivec2 texel, uint width) { return texelFetch(surface, texel, 0); }
#endif
