// kd-restart, kd-backtrack, kd-pushdown, kd-shortstack, kd-pushdown-shortstack
// or kd-stack traversal and intersection (the defines of kd_traversal.glsl):
// up to uLoopLimit steps of kd_traversal.glsl per pass. KD_RECORD: the ray's
// root, push-down flag and stack live in kd_ray_record.glsl's buffer.
#extension GL_ARB_shader_group_vote : require
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#ifdef KD_RECORD
#include "kd/kd_ray_record.glsl"
#endif
#include "kd/kd_traversal.glsl"

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
  KdRay ray;
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
  ray.sceneMax = aux.w;
  ray.hit = readElement(uHit);
  ray.done = false;
  ray.root = 0u;
  ray.pushDown = true;
  ray.top = 0u;
  ray.count = 0u;
#ifdef KD_RECORD
  ray.record = kdRecordBase();
  ray.root = unpackIndex(kdRecords[ray.record]);
  ray.top = unpackIndex(kdRecords[ray.record + 1u]);
  ray.count = unpackIndex(kdRecords[ray.record + 2u]);
  ray.pushDown = kdRecords[ray.record + 3u] != 0.0;
#endif
  // The group vote ends the loop once every lane is done: llvmpipe runs a
  // loop whose body touches a storage buffer to its bound otherwise.
  for (int i = 0; i < uLoopLimit; ++i) {
    if (allInvocationsARB(ray.done)) break;
    if (!ray.done) kdStep(ray, uNodes, uLists, uTriangles);
  }
#ifdef KD_RECORD
  kdRecords[ray.record] = packIndex(ray.root);
  kdRecords[ray.record + 1u] = packIndex(ray.top);
  kdRecords[ray.record + 2u] = packIndex(ray.count);
  kdRecords[ray.record + 3u] = ray.pushDown ? 1.0 : 0.0;
#endif
  outState = vec4(packIndex(ray.node), ray.steps, ray.tests, ray.done ? 0.0 : 1.0);
  outHit = ray.hit;
  outAux = vec4(ray.mode, ray.tMin, ray.tMax, ray.sceneMax);
}
