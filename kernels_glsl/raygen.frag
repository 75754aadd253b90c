// Ray generation: one primary ray per element, by the camera contract
// (camera.glsl), and a fresh traversal state.
#include "texel_address.glsl"
#include "ray_kinds.glsl"
#include "camera.glsl"

layout(early_fragment_tests) in;

layout(location = 0) out vec4 outOrigin;      // xyz, ray kind
layout(location = 1) out vec4 outDirection;   // xyz, tMax
layout(location = 2) out vec4 outState;       // traversal state
layout(location = 3) out vec4 outHit;         // t, u, v, packed id
layout(location = 4) out vec4 outColor;       // accumulated radiance
layout(location = 5) out vec4 outThroughput;  // rgb, w: traversal steps so far
layout(location = 6) out vec4 outPending;     // rgb awaiting a shadow ray, w: triangle tests so far

void main() {
  outOrigin = vec4(uEye, RAY_NEAREST);
  outDirection = vec4(cameraRayDirection(), INF);
  outState = vec4(packIndex(0u), 0.0, 0.0, 1.0);
  outHit = vec4(INF, 0.0, 0.0, packIndex(0u));
  outColor = vec4(0.0);
  outThroughput = vec4(1.0, 1.0, 1.0, 0.0);
  outPending = vec4(0.0);
}
