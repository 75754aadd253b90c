// Runs one shared GLSL function per element so tests can compare it with its
// C++ twin (tests/stream_kernels_test.cpp). Chosen by a define:
//   TEST_FETCH:    out = fetchTexel(uData, element index)
//   TEST_FETCH_LARGE: out = fetchTexel(uLargeData, element index), a LargeConstStream
//   TEST_SLAB:     out.x = intersectsBox(origin in0, invDir of in1, lo in2, hi in3, tBest in3.w)
//   TEST_TRIANGLE: out = the hit after intersectTriangle(origin in0, dir in1, a in2, b in3, c in4, id in4.w)
//                  from a hit record (tBest in1.w, 0, 0, -1)
//   TEST_STORAGE:  storage[element index] += element index + 1; out.x = the sum so far (a pass's
//                  writes must reach the next pass)
//   TEST_AO_HASH:  h = pcgHash(pixel in0.x ^ pcgHash(sample in0.y)); out = (h >> 8, h & 255, aoRandom(in0.x, in0.y))
//   TEST_AO_DIRECTION: out.xyz = aoDirection(normal in0.xyz, u in1.xy)
//   TEST_CONE_TRIANGLE: out.xy = (met ? 1 : 0, t) of coneMeetsTriangle over case `element index` of the
//                  storage buffer: 32 floats a case, the apex and triangle as floats, the unit axis,
//                  cos and sin of the half-angle as doubles (two words each, low first)
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ao_sampling.glsl"
#ifdef TEST_CONE_TRIANGLE
#include "cone/cone_tests.glsl"
#endif

uniform ConstStream uData;
uniform LargeConstStream uLargeData;
uniform sampler2D uIn0;
uniform sampler2D uIn1;
uniform sampler2D uIn2;
uniform sampler2D uIn3;
uniform sampler2D uIn4;
uniform int uWidth;
#if defined(TEST_STORAGE) || defined(TEST_CONE_TRIANGLE)
layout(std430, binding = 0) buffer TestStorage { float storage[]; };
#endif

layout(location = 0) out vec4 outResult;

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
#if defined(TEST_FETCH)
  uint index = uint(gl_FragCoord.y) * uint(uWidth) + uint(gl_FragCoord.x);
  outResult = fetchTexel(uData, index);
#elif defined(TEST_FETCH_LARGE)
  uint index = uint(gl_FragCoord.y) * uint(uWidth) + uint(gl_FragCoord.x);
  outResult = fetchTexel(uLargeData, index);
#elif defined(TEST_SLAB)
  vec4 hi = readElement(uIn3);
  bool hit = intersectsBox(readElement(uIn0).xyz, safeInverse(readElement(uIn1).xyz), readElement(uIn2).xyz, hi.xyz, hi.w);
  outResult = vec4(hit ? 1.0 : 0.0, 0.0, 0.0, 0.0);
#elif defined(TEST_TRIANGLE)
  vec4 dir = readElement(uIn1);
  vec4 c = readElement(uIn4);
  vec4 hit = vec4(dir.w, 0.0, 0.0, -1.0);
  intersectTriangle(readElement(uIn0).xyz, dir.xyz, readElement(uIn2).xyz, readElement(uIn3).xyz, c.xyz, c.w, hit);
  outResult = hit;
#elif defined(TEST_STORAGE)
  uint index = uint(gl_FragCoord.y) * uint(uWidth) + uint(gl_FragCoord.x);
  storage[index] += float(index + 1u);
  outResult = vec4(storage[index], 0.0, 0.0, 0.0);
#elif defined(TEST_AO_HASH)
  uvec2 ps = uvec2(readElement(uIn0).xy);
  uint h = pcgHash(ps.x ^ pcgHash(ps.y));
  outResult = vec4(float(h >> 8u), float(h & 255u), aoRandom(ps.x, ps.y));
#elif defined(TEST_AO_DIRECTION)
  outResult = vec4(aoDirection(readElement(uIn0).xyz, readElement(uIn1).xy), 0.0);
#elif defined(TEST_CONE_TRIANGLE)
  uint b = 32u * (uint(gl_FragCoord.y) * uint(uWidth) + uint(gl_FragCoord.x));
  vec3 f[4];
  for (uint i = 0u; i < 4u; ++i) f[i] = vec3(storage[b + 3u * i], storage[b + 3u * i + 1u], storage[b + 3u * i + 2u]);
  double d[5];
  for (uint i = 0u; i < 5u; ++i)
    d[i] = packDouble2x32(
        uvec2(floatBitsToUint(storage[b + 12u + 2u * i]), floatBitsToUint(storage[b + 13u + 2u * i])));
  float t;
  bool met =
      coneMeetsTriangle(dvec3(f[0]), dvec3(d[0], d[1], d[2]), d[3], d[4], dvec3(f[1]), dvec3(f[2]), dvec3(f[3]), t);
  outResult = vec4(met ? 1.0 : 0.0, t, 0.0, 0.0);
#endif
}
