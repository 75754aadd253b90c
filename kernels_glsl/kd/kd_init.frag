// kd-tree traversal set-up (thesis 8.5.1): the interval where the ray is
// inside the scene box, clipped to [0, tMax]; rays that miss it finish here.
#include "texel_address.glsl"
#include "intersect.glsl"
#ifdef KD_RECORD
#include "kd/kd_ray_record.glsl"
#endif

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform vec3 uSceneMin;
uniform vec3 uSceneMax;
#ifdef KD_CONTINUE
// A second tree after a first (--dynamic two-trees): the hit surface holds
// the first tree's hit and the state surface its step and test counts.
#include "ray_kinds.glsl"
uniform sampler2D uState;
uniform sampler2D uHit;
#endif

layout(location = 0) out vec4 outState;  // packed node, steps, tests, hasWork
layout(location = 1) out vec4 outAux;    // mode, tMin, tMax, sceneMax

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  float tNear, tFar;
  bool inside = clipToBox(origin.xyz, safeInverse(direction.xyz), uSceneMin, uSceneMax, tNear, tFar);
  float tMin = max(tNear, 0.0);
  float tMax = min(tFar, direction.w);
  // An empty scene's box (min > max, infinite) would clip to everything.
  bool sceneEmpty = any(greaterThan(uSceneMin, uSceneMax));
  bool hasWork = inside && tMin <= tMax && !sceneEmpty;
  vec2 counts = vec2(0.0);
#ifdef KD_CONTINUE
  // Only a hit nearer than the first tree's can matter; a shadow ray that
  // hit is done.
  vec4 hit = readElement(uHit);
  tMax = min(tMax, hit.x);
  hasWork = hasWork && tMin <= tMax && !(origin.w == RAY_SHADOW && hit.x < direction.w);
  counts = readElement(uState).yz;
#endif
  outState = vec4(packIndex(0u), counts, hasWork ? 1.0 : 0.0);
  outAux = vec4(-1.0, tMin, tMax, tMax);
#ifdef KD_RECORD
  // Restart from the root, push-down on, empty stack.
  uint record = kdRecordBase();
  kdRecords[record] = packIndex(0u);
  kdRecords[record + 1u] = packIndex(0u);
  kdRecords[record + 2u] = packIndex(0u);
  kdRecords[record + 3u] = 1.0;
#endif
}
