#pragma once
// The watertight ray/triangle test of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection" (JCGT 2(1), 2013), two-sided, with the same hit
// rule as Möller–Trumbore in geometry.h. kernels_glsl/watertight_triangle.glsl
// performs the same operations in the same order.
//
// Why it is watertight: the vertices are moved into a frame where the ray is
// the +z axis through the origin (a shear that depends on the ray only), and
// the 2D edge functions U, V, W are computed from the sheared vertices. Two
// triangles sharing an edge compute that edge's function from the same two
// sheared vertices in the opposite order, which gives exactly the negated
// value in IEEE arithmetic (round to nearest is symmetric), so a ray can
// never fall between them. Edge functions of exactly zero are recomputed in
// double, where the float products are exact, as the paper does. This holds
// only without fused multiply-adds: the project is built in ISO C++ mode
// (-ffp-contract=off) and the GLSL uses `precise`.

#include <cmath>
#include <cstdint>
#include <utility>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace {

// A 2x2 determinant a*d - b*c of floats, rounded once to double (the
// products are exact there) and then to float.
inline float edgeFunctionInDouble(float a, float d, float b, float c) {
  return static_cast<float>(double(a) * double(d) - double(b) * double(c));
}

// Updates `best` and returns true when the triangle is hit strictly in front
// of the origin and strictly before best.t; u, v weight v1 and v2. The ray
// set-up (kx, ky, kz and the shear) is recomputed per call, as the GPU
// kernels do; the paper does it once per ray.
inline bool intersectTriangleWatertight(const glm::vec3& origin, const glm::vec3& dir, const Triangle& tri,
                                        uint32_t id, Hit& best) {
  // z is the axis along which the direction is largest; x and y follow
  // cyclically, swapped when dir.z < 0 so the winding is kept.
  const glm::vec3 a = glm::abs(dir);
  const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  if (dir[kz] == 0.0f) return false;  // a zero direction
  if (dir[kz] < 0.0f) std::swap(kx, ky);
  // A reciprocal and products rather than the paper's quotients: GLSL
  // drivers may lower a / b to a * (1 / b), which would break the agreement.
  const float sz = 1.0f / dir[kz];
  const float sx = dir[kx] * sz;
  const float sy = dir[ky] * sz;

  // The vertices relative to the origin, sheared so the ray is the z axis.
  const glm::vec3 pa = tri.v0 - origin;
  const glm::vec3 pb = tri.v1 - origin;
  const glm::vec3 pc = tri.v2 - origin;
  const float ax = pa[kx] - sx * pa[kz];
  const float ay = pa[ky] - sy * pa[kz];
  const float bx = pb[kx] - sx * pb[kz];
  const float by = pb[ky] - sy * pb[kz];
  const float cx = pc[kx] - sx * pc[kz];
  const float cy = pc[ky] - sy * pc[kz];

  // Edge functions: U weights v0, V weights v1, W weights v2 (unnormalised).
  float U = cx * by - cy * bx;
  float V = ax * cy - ay * cx;
  float W = bx * ay - by * ax;
  if (U == 0.0f || V == 0.0f || W == 0.0f) {
    U = edgeFunctionInDouble(cx, by, cy, bx);
    V = edgeFunctionInDouble(ax, cy, ay, cx);
    W = edgeFunctionInDouble(bx, ay, by, ax);
  }
  // Two-sided: inside when no two edge functions have opposite signs.
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
  const float det = U + V + W;
  if (det == 0.0f) return false;  // the ray lies in the triangle's plane, or a degenerate triangle

  const float az = sz * pa[kz];
  const float bz = sz * pb[kz];
  const float cz = sz * pc[kz];
  const float T = U * az + V * bz + W * cz;
  const float invDet = 1.0f / det;
  const float t = T * invDet;
  if (!(t > 0.0f && t < best.t)) return false;
  best = Hit{t, V * invDet, W * invDet, id};
  return true;
}

}  // namespace passtrace
