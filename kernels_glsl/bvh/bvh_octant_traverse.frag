// bvh_traverse.frag's escape-index walk over the sequence of the ray's octant
// (accel/bvh/octant_sequences.h): eight sequences of uSequenceSize texels
// back to back, children near-first for their octant. The state keeps the
// index inside the ray's own sequence, so it resumes exactly as kk-bvh's.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;      // packed next index, steps, triangle tests, active
uniform sampler2D uHit;
uniform ConstStream uSequences;  // the eight escape-index sequences
uniform uint uSequenceSize;      // texels in one sequence: the end of traversal
uniform int uLoopLimit;          // traversal steps per pass (tracy's -l)

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;

// As rayOctant in accel/bvh/octant_sequences.h: a bit per negative component.
uint rayOctant(vec3 direction) {
  return (direction.x < 0.0 ? 1u : 0u) | (direction.y < 0.0 ? 2u : 0u) | (direction.z < 0.0 ? 4u : 0u);
}

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  bool anyHit = origin.w == RAY_SHADOW;
  vec3 invDir = safeInverse(direction.xyz);
  uint base = rayOctant(direction.xyz) * uSequenceSize;

  uint index = unpackIndex(state.x);
  float steps = state.y, tests = state.z;
  int budget = uLoopLimit;
  while (budget > 0 && index < uSequenceSize) {
    // Boxes until a triangle: llvmpipe runs both sides of a divergent branch, so
    // the triangle test stays out of this loop and runs once per triangle below.
    vec4 first = fetchTexel(uSequences, base + index);
    while (budget > 0 && index < uSequenceSize && first.w >= 0.0) {
      vec4 second = fetchTexel(uSequences, base + index + 1u);
      steps += 1.0;
      budget -= 1;
      bool enter = intersectsBox(origin.xyz, invDir, first.xyz, second.xyz, hit.x);
      index = enter ? index + 2u : unpackIndex(first.w);
      if (index < uSequenceSize) first = fetchTexel(uSequences, base + index);
    }
    if (budget > 0 && index < uSequenceSize) {
      vec4 second = fetchTexel(uSequences, base + index + 1u);
      vec4 third = fetchTexel(uSequences, base + index + 2u);
      steps += 1.0;
      budget -= 1;
      tests += 1.0;
      bool found = intersectTriangle(origin.xyz, direction.xyz, first.xyz, second.xyz, third.xyz, second.w, hit);
      index = (found && anyHit) ? uSequenceSize : index + 3u;
    }
  }
  outState = vec4(packIndex(index), steps, tests, index < uSequenceSize ? 1.0 : 0.0);
  outHit = hit;
}
