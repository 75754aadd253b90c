// Escape-index BVH traversal and intersection (thesis 9.4, algorithm 4): the
// tree is stored as its depth-first traversal sequence (accel/bvh/escape_sequence.h).
// A box is 2 texels (min, packed escape index; max); a triangle 3 texels
// (v0, -1; v1, packed triangle id; v2). Hitting a box steps into it, missing
// it jumps to its escape index; the loop stops after uLoopLimit steps and the
// next pass resumes from the saved index.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;      // packed next index, steps, triangle tests, active
uniform sampler2D uHit;
uniform ConstStream uSequence;  // the escape-index sequence
uniform uint uSequenceSize;    // texels in the sequence: the end of traversal
uniform int uLoopLimit;        // traversal steps per pass (tracy's -l)

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  bool anyHit = origin.w == RAY_SHADOW;
  vec3 invDir = safeInverse(direction.xyz);

  uint index = unpackIndex(state.x);
  float steps = state.y, tests = state.z;
  for (int i = 0; i < uLoopLimit && index < uSequenceSize; ++i) {
    vec4 first = fetchTexel(uSequence, index);
    vec4 second = fetchTexel(uSequence, index + 1u);
    steps += 1.0;
    if (first.w >= 0.0) {
      bool enter = intersectsBox(origin.xyz, invDir, first.xyz, second.xyz, hit.x);
      index = enter ? index + 2u : unpackIndex(first.w);
    } else {
      vec4 third = fetchTexel(uSequence, index + 2u);
      tests += 1.0;
      bool found = intersectTriangle(origin.xyz, direction.xyz, first.xyz, second.xyz, third.xyz, second.w, hit);
      index = (found && anyHit) ? uSequenceSize : index + 3u;
    }
  }
  outState = vec4(packIndex(index), steps, tests, index < uSequenceSize ? 1.0 : 0.0);
  outHit = hit;
}
