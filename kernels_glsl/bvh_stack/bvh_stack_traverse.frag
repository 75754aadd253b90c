// Stack BVH traversal and intersection: up to uLoopLimit steps of
// bvh_stack_traversal.glsl per pass; the stack lives in the ray's record.
#extension GL_ARB_shader_group_vote : require
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#include "bvh_stack/bvh_stack_record.glsl"
#include "bvh_stack/bvh_stack_traversal.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uAux;
uniform ConstStream uNodes;
uniform ConstStream uReferences;
uniform ConstStream uTriangles;
uniform int uLoopLimit;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;
layout(location = 2) out vec4 outAux;

void main() {
  // Helper lanes' storage writes are discarded (their walk could loop to -l) and reads may lie past
  // the buffer (docs/design.md).
  if (gl_HelperInvocation) return;
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  BvhRay ray;
  ray.origin = origin.xyz;
  ray.direction = direction.xyz;
  ray.invDir = safeInverse(direction.xyz);
  ray.anyHit = origin.w == RAY_SHADOW;
  ray.link = unpackIndex(state.x);
  ray.steps = state.y;
  ray.tests = state.z;
  ray.count = uint(readElement(uAux).x);
  ray.hit = readElement(uHit);
  ray.done = false;
  ray.record = bvhRecordBase();
  ray.depth = unpackIndex(bvhRecords[ray.record]);
  // The group vote ends the loop once every lane is done: llvmpipe runs a
  // loop whose body touches a storage buffer to its bound otherwise.
  for (int i = 0; i < uLoopLimit; ++i) {
    if (allInvocationsARB(ray.done)) break;
    if (!ray.done) bvhStep(ray, uNodes, uReferences, uTriangles);
  }
  bvhRecords[ray.record] = packIndex(ray.depth);
  outState = vec4(packIndex(ray.link), ray.steps, ray.tests, ray.done ? 0.0 : 1.0);
  outHit = ray.hit;
  outAux = vec4(float(ray.count), 0.0, 0.0, 0.0);
}
