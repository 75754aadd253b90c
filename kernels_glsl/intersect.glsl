// The slab test and the Möller–Trumbore test, operation for operation as in
// accel/geometry/geometry.h. `precise` forbids the compiler from fusing or reordering
// them, so GPU and CPU results agree wherever the driver keeps IEEE order.
// With WATERTIGHT_TRIANGLES defined (--triangle-test watertight),
// intersectTriangle runs the watertight test instead.
#include "watertight_triangle.glsl"

vec3 safeInverse(vec3 d) {
  const float tiny = 1e-20;
  vec3 signedTiny = mix(vec3(tiny), vec3(-tiny), lessThan(d, vec3(0.0)));
  return 1.0 / mix(d, signedTiny, lessThan(abs(d), vec3(tiny)));
}

// The interval [tNear, tFar] where the ray's line is inside [lo, hi]; false
// when empty. A ray parallel to a slab (|invDir| > 1e19, direction component
// below 1e-19) is inside it for all t or for none: with the tiny stand-in
// alone an origin lying exactly on the max face would miss.
// `parallel` given apart: for rays whose inverse direction is scaled (box_grid.glsl).
bool clipToBox(vec3 origin, vec3 invDir, bvec3 parallel, vec3 lo, vec3 hi, out float tNear, out float tFar) {
  precise vec3 t0 = (lo - origin) * invDir;
  precise vec3 t1 = (hi - origin) * invDir;
  bvec3 inside = equal(step(lo, origin) * step(origin, hi), vec3(1.0));
  vec3 tSmall = mix(min(t0, t1), mix(vec3(INF), vec3(-INF), inside), parallel);
  vec3 tLarge = mix(max(t0, t1), mix(vec3(-INF), vec3(INF), inside), parallel);
  tNear = max(max(tSmall.x, tSmall.y), tSmall.z);
  tFar = min(min(tLarge.x, tLarge.y), tLarge.z);
  return tNear <= tFar;
}

bvec3 parallelSlabs(vec3 invDir) { return greaterThan(abs(invDir), vec3(1e19)); }

bool clipToBox(vec3 origin, vec3 invDir, vec3 lo, vec3 hi, out float tNear, out float tFar) {
  return clipToBox(origin, invDir, parallelSlabs(invDir), lo, hi, tNear, tFar);
}

// Does the ray enter [lo, hi] before tBest, and not entirely behind it?
// Conservative: the exit t is enlarged by 3 ulps of 1 (kRobustExitScale in
// accel/geometry/geometry.h, 1 + 3 * 2^-23) so rounding never loses a box the ray
// touches at a corner.
bool intersectsBox(vec3 origin, vec3 invDir, vec3 lo, vec3 hi, float tBest) {
  float tNear, tFar;
  clipToBox(origin, invDir, lo, hi, tNear, tFar);
  precise float tExit = tFar * 1.00000035762786865234375;
  return tNear <= tExit && tExit >= 0.0 && tNear < tBest;
}

// Two-sided Möller–Trumbore. `hit` is (t, u, v, packed id); it is replaced
// when the triangle is hit in front of the origin and strictly before hit.x.
bool intersectTriangleMollerTrumbore(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c, float packedId, inout vec4 hit) {
  precise vec3 e1 = b - a;
  precise vec3 e2 = c - a;
  precise vec3 p = cross(dir, e2);
  precise float det = dot(p, e1);
  if (det == 0.0) return false;
  precise float invDet = 1.0 / det;
  precise vec3 tvec = origin - a;
  precise float u = dot(p, tvec) * invDet;
  precise vec3 q = cross(tvec, e1);
  precise float v = dot(q, dir) * invDet;
  precise float t = dot(q, e2) * invDet;
  if (!(u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < hit.x)) return false;
  hit = vec4(t, u, v, packedId);
  return true;
}

// The test every kernel calls, chosen when the kernel is compiled.
bool intersectTriangle(vec3 origin, vec3 dir, vec3 a, vec3 b, vec3 c, float packedId, inout vec4 hit) {
#ifdef WATERTIGHT_TRIANGLES
  return intersectTriangleWatertight(origin, dir, a, b, c, packedId, hit);
#else
  return intersectTriangleMollerTrumbore(origin, dir, a, b, c, packedId, hit);
#endif
}
