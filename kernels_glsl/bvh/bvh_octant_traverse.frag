// bvh-octant's traversal pass: bvh_octant_walk.glsl over every active ray,
// resuming from the state the previous pass saved.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "bvh/bvh_octant_walk.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;      // packed next index, steps, triangle tests, active
uniform sampler2D uHit;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  uint index = unpackIndex(state.x);
  float steps = state.y, tests = state.z;
  octantWalk(origin.xyz, direction.xyz, origin.w == RAY_SHADOW, index, steps, tests, hit);
  outState = vec4(packIndex(index), steps, tests, index < uSequenceSize ? 1.0 : 0.0);
  outHit = hit;
}
