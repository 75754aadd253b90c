// BIH traversal and intersection: up to uLoopLimit steps of bih_traversal.glsl
// per pass; the stack lives in bih_ray_record.glsl's buffer.
#extension GL_ARB_shader_group_vote : require
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#include "bih/bih_ray_record.glsl"
#include "bih/bih_slack.glsl"
#include "bih/bih_traversal.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uAux;
uniform ConstStream uNodes;
uniform ConstStream uLists;
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
  vec4 aux = readElement(uAux);
  BihRay ray;
  ray.origin = origin.xyz;
  ray.direction = direction.xyz;
  ray.invDir = safeInverse(direction.xyz);
  ray.anyHit = origin.w == RAY_SHADOW;
  ray.node = unpackIndex(state.x);
  ray.steps = state.y;
  ray.tests = state.z;
  ray.mode = aux.x;
  ray.tMin = aux.y;
  ray.tMax = aux.z;
  ray.hit = readElement(uHit);
  ray.done = false;
  ray.record = bihRecordBase();
  ray.count = unpackIndex(bihRecords[ray.record]);
  // The group vote ends the loop once every lane is done: llvmpipe runs a
  // loop whose body touches a storage buffer to its bound otherwise.
  for (int i = 0; i < uLoopLimit; ++i) {
    if (allInvocationsARB(ray.done)) break;
    if (!ray.done) bihStep(ray, uNodes, uLists, uTriangles);
  }
  bihRecords[ray.record] = packIndex(ray.count);
  outState = vec4(packIndex(ray.node), ray.steps, ray.tests, ray.done ? 0.0 : 1.0);
  outHit = ray.hit;
  outAux = vec4(ray.mode, ray.tMin, ray.tMax, 0.0);
}
