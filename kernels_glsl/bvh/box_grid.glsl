// Boxes of one texel on a scene-wide grid, tested in grid units, operation
// for operation as accel/bvh/box_grid.h (which says why it is conservative).
// Needs intersect.glsl.

uniform vec3 uBoxGridOrigin;   // plane q of axis a is origin[a] + q * step[a]
uniform vec3 uBoxGridStep;     // powers of two
uniform vec3 uBoxGridInvStep;  // 1 / step, exact

struct GridRay {
  vec3 origin;
  vec3 invDir;
  bvec3 parallel;
};

GridRay gridRay(vec3 origin, vec3 invDir) {
  precise vec3 o = (origin - uBoxGridOrigin) * uBoxGridInvStep;
  return GridRay(o, invDir * uBoxGridStep, parallelSlabs(invDir));
}

// A box texel's xyz: 15 bits of low plane, 15 of high (bit 30 a tag that keeps the float normal).
bool intersectsGridBox(GridRay ray, vec3 planes, float tBest) {
  uvec3 bits = floatBitsToUint(planes);
  float tNear, tFar;
  clipToBox(ray.origin, ray.invDir, ray.parallel, vec3((bits >> 15u) & 0x7FFFu), vec3(bits & 0x7FFFu), tNear, tFar);
  precise float tExit = tFar * 1.000000476837158203125;  // kGridExitScale: 1 + 4 * 2^-23
  return tNear <= tExit && tExit >= 0.0 && tNear < tBest;
}
