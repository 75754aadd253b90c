#pragma once
// The geometric tests of a cone query.
//
// Cone against an axis-aligned plane x_a = d (seed Eq. 2): the cone's cross
// section at axis distance t is a disk of radius t tan(alpha) around
// S + t v, whose extent along axis a is
//   [S_a + t (v_a - k), S_a + t (v_a + k)],  k = tan(alpha) sqrt(1 - v_a^2),
// so the cone edges meet the plane at t = (d - S_a) / (v_a -+ k) (Eq. 2).
// Each side of the plane is a linear inequality in t; a traversal keeps an
// interval [t0, t1] and cuts it with those inequalities (coneClip).
//
// Cone against a box (Listing 2, "cone frustum vs AABB"): the slab test with
// each axis's two inequalities  S_a + t (v_a - k) <= max_a  and
// S_a + t (v_a + k) >= min_a. Solving them by the sign of the denominator
// gives exactly Figure 5's cases (origin between the planes: only an upper
// bound or none; outside: a range, a half-line, or a miss). The digest's
// warning: the public "improved" code takes min/max of the four t values
// regardless of the denominators' signs (and maps negative t to +inf), which
// turns a lower bound into an upper one when an edge points away from the
// plane; here each bound's side follows its denominator's sign.
//
// The interval is conservative: k is widened by kConeSlack (relative) so
// that rounding never culls a node holding a triangle the exact test
// (coneMeetsTriangle) accepts; kd-tree and BVH then count the same triangles.

#include "accel/cone/cone.h"

namespace passtrace {

inline constexpr float kConeSlack = 1e-4f;

// Restricts [t0, t1] to { t : c + m t <= 0 }.
inline void coneClip(float c, float m, float& t0, float& t1) {
  if (m > 0.0f) t1 = std::min(t1, -c / m);
  else if (m < 0.0f) t0 = std::max(t0, -c / m);
  else if (c > 0.0f) t0 = kInfinity;
}

// k of Eq. 2 for every axis, widened for conservative culling.
inline glm::vec3 coneSpread(const Cone& cone) {
  const float tanA = std::tan(cone.halfAngle) * (1.0f + kConeSlack) + 1e-6f;
  glm::vec3 k;
  for (int a = 0; a < 3; ++a) k[a] = tanA * std::sqrt(std::max(0.0f, 1.0f - cone.axis[a] * cone.axis[a])) + 1e-6f;
  return k;
}

// Does the interval survive, with a relative tolerance for rounding in -c/m?
inline bool coneIntervalOpen(float t0, float t1) { return t0 <= t1 + kConeSlack * std::abs(t1) + 1e-30f; }

// The part of the cone below (side 0: x_a <= d) or above (side 1: x_a >= d) a split plane.
inline bool coneSide(const Cone& cone, const glm::vec3& k, int axis, float d, int side, float& t0, float& t1) {
  const float c = cone.apex[axis] - d;
  if (side == 0) coneClip(c, cone.axis[axis] - k[axis], t0, t1);
  else coneClip(-c, -(cone.axis[axis] + k[axis]), t0, t1);
  return coneIntervalOpen(t0, t1);
}

// Cone against a box: [t0, t1] cut to the axis distances where the cone can
// be inside the box. False when it never is.
inline bool coneBox(const Cone& cone, const glm::vec3& k, const Aabb& box, float& t0, float& t1) {
  for (int a = 0; a < 3; ++a) {
    coneClip(cone.apex[a] - box.max[a], cone.axis[a] - k[a], t0, t1);
    coneClip(box.min[a] - cone.apex[a], -(cone.axis[a] + k[a]), t0, t1);
  }
  return coneIntervalOpen(t0, t1);
}

// The exact cone/triangle test (cone_tests.cpp). The cone meets a triangle
// iff its axis passes through the triangle or an edge of the triangle comes
// inside the cone: the cone's section by the triangle's plane is convex, and
// if no edge reaches it while it overlaps the triangle it lies inside the
// triangle, so it is bounded (an ellipse) and holds the axis's crossing.
// (Only an apex lying in the triangle's plane escapes this; a camera apex
// does not.) On success t is the axis distance of the triangle's nearest
// point inside the cone: the least of the axis crossing, the edges' points
// inside the cone, and the section's extreme points inside the triangle
// (on the generators in the plane of axis and normal). Computed in double.
bool coneMeetsTriangle(const Cone& cone, const Triangle& tri, float& t);

// Nearest first, ties by id: the order of ConeResult::hits.
inline bool coneHitBefore(const ConeHit& a, const ConeHit& b) { return a.t < b.t || (a.t == b.t && a.id < b.id); }

}  // namespace passtrace
