#include "accel/cone/cone_tests.h"

#include <algorithm>

namespace passtrace {
namespace {

using glm::dvec3;

// Moller-Trumbore in double, edges included: the axis distance where the
// axis crosses the triangle, or -1.
double axisCrossing(const dvec3& s, const dvec3& v, const dvec3& p0, const dvec3& p1, const dvec3& p2) {
  const dvec3 e1 = p1 - p0, e2 = p2 - p0;
  const dvec3 p = glm::cross(v, e2);
  const double det = glm::dot(p, e1);
  if (det == 0.0) return -1.0;
  const dvec3 tv = s - p0;
  const double u = glm::dot(p, tv) / det;
  const dvec3 q = glm::cross(tv, e1);
  const double w = glm::dot(q, v) / det;
  const double t = glm::dot(q, e2) / det;
  return u >= 0.0 && w >= 0.0 && u + w <= 1.0 && t >= 0.0 ? t : -1.0;
}

// Edge a + s (b - a), s in [0, 1]. A point P is inside the cone iff
// g = (P - S).v >= 0 and f = g^2 - cos^2(alpha) |P - S|^2 >= 0; g is linear
// and f quadratic in s. The set { g >= 0 } is an interval [s0, s1]; the
// extreme points of { f >= 0 } inside it are s0, s1 or roots of f, so g's
// smallest value over the edge's part inside the cone is at one of those.
// Returns that value, or -1 when the edge stays outside.
double edgeNearest(const dvec3& s, const dvec3& v, double cos2, const dvec3& a, const dvec3& b) {
  const dvec3 d0 = a - s, e = b - a;
  const double g0 = glm::dot(d0, v), g1 = glm::dot(e, v);
  double s0 = 0.0, s1 = 1.0;
  if (g1 > 0.0) s0 = std::max(s0, -g0 / g1);
  else if (g1 < 0.0) s1 = std::min(s1, -g0 / g1);
  else if (g0 < 0.0) return -1.0;
  if (s0 > s1) return -1.0;
  const double qa = g1 * g1 - cos2 * glm::dot(e, e);
  const double qh = g0 * g1 - cos2 * glm::dot(d0, e);
  const double qc = g0 * g0 - cos2 * glm::dot(d0, d0);
  const auto f = [&](double x) { return (qa * x + 2.0 * qh) * x + qc; };
  double best = -1.0;
  // A root of f is on the cone's surface up to rounding; an edge nearly
  // parallel to the axis makes qa tiny and its roots inexact, so a root
  // must still satisfy f >= 0 to 1e-13 of |D|^2 (3e-7 of the distance).
  const auto consider = [&](double x, bool onBoundary) {
    if (x < s0 || x > s1) return;
    const dvec3 p = d0 + x * e;
    if (f(x) < (onBoundary ? -1e-13 * glm::dot(p, p) : 0.0)) return;
    const double g = std::max(0.0, g0 + x * g1);
    if (best < 0.0 || g < best) best = g;
  };
  consider(s0, false);
  consider(s1, false);
  if (qa != 0.0) {
    const double disc = qh * qh - qa * qc;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      consider((-qh - r) / qa, true);
      consider((-qh + r) / qa, true);
    }
  } else if (qh != 0.0) {
    consider(-qc / (2.0 * qh), true);
  }
  return best;
}

}  // namespace

bool coneMeetsTriangle(const Cone& cone, const Triangle& tri, float& t) {
  // The float axis is unit only to 1e-7, which would swamp f's cancellation.
  const dvec3 s(cone.apex), v = glm::normalize(dvec3(cone.axis)), p0(tri.v0), p1(tri.v1), p2(tri.v2);
  const double c = std::cos(double(cone.halfAngle));
  const double cos2 = c * c;
  double best = axisCrossing(s, v, p0, p1, p2);
  for (const auto& [a, b] : {std::pair{p0, p1}, std::pair{p1, p2}, std::pair{p2, p0}}) {
    const double g = edgeNearest(s, v, cos2, a, b);
    if (g >= 0.0 && (best < 0.0 || g < best)) best = g;
  }
  if (best < 0.0) return false;
  // Inside the triangle, the section's nearest and farthest points lie on
  // its symmetry line: the generators in the plane of the axis and the
  // triangle's normal. Where one crosses the triangle, it is a candidate.
  const dvec3 n = glm::cross(p1 - p0, p2 - p0);
  const dvec3 w = n - glm::dot(n, v) * v;
  const double wl = glm::length(w);
  if (wl > 0.0) {
    const double sinA = std::sin(double(cone.halfAngle));
    for (double side : {-1.0, 1.0}) {
      const double lambda = axisCrossing(s, c * v + side * sinA * (w / wl), p0, p1, p2);
      if (lambda >= 0.0) best = std::min(best, lambda * c);
    }
  }
  t = float(best);
  return true;
}

}  // namespace passtrace
