// Uniform-grid traversal set-up (thesis 7.4.1): the first cell the ray
// enters (or starts in) and the t of its next boundary crossing per axis.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#include "grid/grid_traversal.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outAux;

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec3 invDir = safeInverse(direction.xyz);
  float tNear, tFar;
  bool inside = clipToBox(origin.xyz, invDir, uGridMin, uGridMin + vec3(uGridResolution) * uCellSize, tNear, tFar);
  float tMin = max(tNear, 0.0);
  bool hasWork = inside && tMin <= min(tFar, direction.w);
  precise vec3 entry = origin.xyz + tMin * direction.xyz;
  // Clamp in float first: a far-away entry point must not overflow the int conversion.
  ivec3 cell = ivec3(clamp(floor((entry - uGridMin) * uInvCellSize), vec3(0.0), vec3(uGridResolution - 1)));
  vec3 lower = uGridMin + vec3(cell) * uCellSize;
  vec3 boundary = mix(lower, lower + uCellSize, greaterThan(direction.xyz, vec3(0.0)));
  precise vec3 tNext = (boundary - origin.xyz) * invDir;
  tNext = mix(tNext, vec3(INF), greaterThan(abs(invDir), vec3(1e19)));
  outState = vec4(packIndex(linearCell(cell)), 0.0, 0.0, hasWork ? 1.0 : 0.0);
  outAux = vec4(tNext, MODE_VISIT);
}
