// The watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013),
// operation for operation as in accel/geometry/watertight_triangle.h (see there for
// why it never leaks). `precise` forbids fused multiply-adds: a fused edge
// function would no longer be the exact negation of its neighbour's.

// a*d - b*c rounded once to double (the float products are exact there), then to float.
float edgeFunctionInDouble(float a, float d, float b, float c) {
  precise double r = double(a) * double(d) - double(b) * double(c);
  return float(r);
}

// Two-sided. `hit` is (t, u, v, packed id); it is replaced when the triangle
// is hit in front of the origin and strictly before hit.x.
bool intersectTriangleWatertight(vec3 origin, vec3 dir, vec3 v0, vec3 v1, vec3 v2, float packedId, inout vec4 hit) {
  // z is the axis along which the direction is largest; x and y follow
  // cyclically, swapped when dir.z < 0 so the winding is kept.
  vec3 a = abs(dir);
  int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  if (dir[kz] == 0.0) return false;
  if (dir[kz] < 0.0) {
    int swapped = kx;
    kx = ky;
    ky = swapped;
  }
  precise float sz = 1.0 / dir[kz];
  precise float sx = dir[kx] * sz;
  precise float sy = dir[ky] * sz;

  // The vertices relative to the origin, sheared so the ray is the z axis.
  precise vec3 pa = v0 - origin;
  precise vec3 pb = v1 - origin;
  precise vec3 pc = v2 - origin;
  precise float ax = pa[kx] - sx * pa[kz];
  precise float ay = pa[ky] - sy * pa[kz];
  precise float bx = pb[kx] - sx * pb[kz];
  precise float by = pb[ky] - sy * pb[kz];
  precise float cx = pc[kx] - sx * pc[kz];
  precise float cy = pc[ky] - sy * pc[kz];

  // Edge functions: U weights v0, V weights v1, W weights v2 (unnormalised).
  precise float U = cx * by - cy * bx;
  precise float V = ax * cy - ay * cx;
  precise float W = bx * ay - by * ax;
  if (U == 0.0 || V == 0.0 || W == 0.0) {
    U = edgeFunctionInDouble(cx, by, cy, bx);
    V = edgeFunctionInDouble(ax, cy, ay, cx);
    W = edgeFunctionInDouble(bx, ay, by, ax);
  }
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
  precise float det = U + V + W;
  if (det == 0.0) return false;

  precise float az = sz * pa[kz];
  precise float bz = sz * pb[kz];
  precise float cz = sz * pc[kz];
  precise float T = U * az + V * bz + W * cz;
  precise float invDet = 1.0 / det;
  precise float t = T * invDet;
  if (!(t > 0.0 && t < hit.x)) return false;
  precise float u = V * invDet;
  precise float v = W * invDet;
  hit = vec4(t, u, v, packedId);
  return true;
}
