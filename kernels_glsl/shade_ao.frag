// --shading ao, one pass; render/ao_shading.cpp is the same computation. A
// primary hit starts the AO rays (any-hit, tMax = uAoDistance) about its
// geometric normal, kept in pending.rgb; color.a counts the samples; each
// unoccluded ray adds 1 / uSamples to the grey. A primary miss shows the
// background.
#include "texel_address.glsl"
#include "ray_kinds.glsl"
#include "triangle_shading.glsl"
#include "ao_sampling.glsl"
#include "row_bands.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uColor;
uniform sampler2D uThroughput;
uniform sampler2D uPending;
uniform vec3 uBackground;
uniform float uEpsilon;
uniform int uSamples;
uniform float uAoDistance;
uniform uint uStreamWidth;

layout(location = 0) out vec4 outOrigin;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outState;
layout(location = 3) out vec4 outHit;
layout(location = 4) out vec4 outColor;
layout(location = 5) out vec4 outThroughput;
layout(location = 6) out vec4 outPending;

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  vec4 color = readElement(uColor);
  vec4 throughput = readElement(uThroughput);
  vec4 pending = readElement(uPending);
  throughput.w += state.y;
  pending.w += state.z;

  bool found = hit.x < direction.w;
  bool next = false;
  vec3 newOrigin = origin.xyz;
  if (origin.w == RAY_NEAREST) {
    if (!found) {
      color.rgb += uBackground;
    } else {
      vec3 geometric = fetchTriangleShading(unpackIndex(hit.w)).geometric;
      pending.rgb = dot(geometric, direction.xyz) > 0.0 ? -geometric : geometric;
      newOrigin = origin.xyz + hit.x * direction.xyz + uEpsilon * pending.rgb;
      color.a = 0.0;
      next = true;
    }
  } else if (origin.w == RAY_SHADOW) {
    if (!found) color.rgb += vec3(1.0 / float(uSamples));
    color.a += 1.0;
    next = int(color.a) < uSamples;
  }
  uvec2 at = uvec2(gl_FragCoord.xy);
  vec3 newDirection = next ? aoDirection(pending.rgb, aoRandom(imageRow(at.y) * uStreamWidth + at.x, uint(color.a)))
                           : direction.xyz;
  float kind = next ? RAY_SHADOW : RAY_NONE;
  float tMax = next ? uAoDistance : INF;
  outOrigin = vec4(newOrigin, kind);
  outDirection = vec4(newDirection, tMax);
  outState = vec4(packIndex(0u), 0.0, 0.0, next ? 1.0 : 0.0);
  outHit = vec4(tMax, 0.0, 0.0, packIndex(0u));
  outColor = color;
  outThroughput = throughput;
  outPending = pending;
}
