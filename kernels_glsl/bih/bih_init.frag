// BIH traversal set-up: the interval where the ray is inside the scene box
// (widened as bihStreamStart does), clipped to [0, tMax]; rays that miss it
// finish here. The stack starts empty.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "bih/bih_ray_record.glsl"
#include "bih/bih_slack.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform vec3 uSceneMin;
uniform vec3 uSceneMax;

layout(location = 0) out vec4 outState;  // packed node, steps, tests, hasWork
layout(location = 1) out vec4 outAux;    // mode, tMin, tMax, 0

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  float tNear, tFar;
  clipToBox(origin.xyz, safeInverse(direction.xyz), uSceneMin, uSceneMax, tNear, tFar);
  float tMin = max(widenDown(tNear), 0.0);
  float tMax = min(widenUp(tFar), direction.w);
  // An empty scene's box (min > max, infinite) would clip to everything.
  bool sceneEmpty = any(greaterThan(uSceneMin, uSceneMax));
  bool hasWork = tMin <= tMax && !sceneEmpty;
  outState = vec4(packIndex(0u), 0.0, 0.0, hasWork ? 1.0 : 0.0);
  outAux = vec4(-1.0, tMin, tMax, 0.0);
  bihRecords[bihRecordBase()] = packIndex(0u);
}
