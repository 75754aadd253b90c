#include "accel/dacrt/cell_tests.h"

#include <algorithm>
#include <array>

namespace passtrace::dacrt {
namespace {

// Does the axis `a` separate the triangle (vertices relative to the box
// centre) from the box of half-extent h?
bool separates(const glm::vec3& a, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
               const glm::vec3& h) {
  const float p0 = glm::dot(a, v0), p1 = glm::dot(a, v1), p2 = glm::dot(a, v2);
  const float r = h.x * std::fabs(a.x) + h.y * std::fabs(a.y) + h.z * std::fabs(a.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

// Is point p inside the (single, forward) cone? In doubles: the test is
// squared below, and the products lose float precision near the boundary.
bool insideCone(const glm::dvec3& w, const glm::dvec3& axis, double cosAngle) {
  const double along = glm::dot(axis, w);
  return along >= 0.0 && along * along >= cosAngle * cosAngle * glm::dot(w, w);
}

// Does the segment e0 + s d, s in [0, 1], meet the cone? Endpoints first,
// then the points where the segment crosses the double cone's surface
// (roots of (axis.w)^2 = cos^2 |w|^2), kept when on the forward nappe.
bool segmentMeetsCone(const glm::dvec3& e0, const glm::dvec3& d, const glm::dvec3& axis, double cosAngle) {
  if (insideCone(e0, axis, cosAngle) || insideCone(e0 + d, axis, cosAngle)) return true;
  const double c = cosAngle * cosAngle;
  const double ad = glm::dot(axis, d), ae = glm::dot(axis, e0);
  const double c2 = ad * ad - c * glm::dot(d, d);
  const double c1 = ad * ae - c * glm::dot(d, e0);
  const double c0 = ae * ae - c * glm::dot(e0, e0);
  const auto forwardAt = [&](double s) { return s >= 0.0 && s <= 1.0 && ae + s * ad >= 0.0; };
  if (std::fabs(c2) < 1e-300) {  // linear: the segment is parallel to a generator
    return c1 != 0.0 && forwardAt(-c0 / (2.0 * c1));
  }
  const double disc = c1 * c1 - c0 * c2;
  if (disc < 0.0) return false;
  const double root = std::sqrt(disc);
  return forwardAt((-c1 - root) / c2) || forwardAt((-c1 + root) / c2);
}

}  // namespace

bool triangleTouchesCell(const Triangle& tri, const Aabb& cell) {
  const Aabb box = loosened(cell);
  const glm::vec3 c = box.center(), h = 0.5f * box.extent();
  const glm::vec3 v0 = tri.v0 - c, v1 = tri.v1 - c, v2 = tri.v2 - c;
  // The box's axes: the triangle's bounds against the box.
  for (int k = 0; k < 3; ++k)
    if (std::min({v0[k], v1[k], v2[k]}) > h[k] || std::max({v0[k], v1[k], v2[k]}) < -h[k]) return false;
  const glm::vec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
  if (separates(glm::cross(e[0], e[1]), v0, v1, v2, h)) return false;  // the triangle's plane
  for (const glm::vec3& edge : e)
    for (int k = 0; k < 3; ++k) {
      glm::vec3 unit(0.0f);
      unit[k] = 1.0f;
      if (separates(glm::cross(edge, unit), v0, v1, v2, h)) return false;
    }
  return true;
}

bool coneTouchesCell(const Cone& cone, const Aabb& cell) {
  const Aabb box = loosened(cell);
  const glm::vec3& a = cone.apex;
  if (a.x >= box.min.x && a.x <= box.max.x && a.y >= box.min.y && a.y <= box.max.y && a.z >= box.min.z &&
      a.z <= box.max.z)
    return true;
  float tNear, tFar;
  if (clipToBox(a, safeInverse(cone.axis), box, tNear, tFar) && tFar >= 0.0f) return true;
  const glm::dvec3 axis(cone.axis);
  const glm::dvec3 lo = glm::dvec3(box.min) - glm::dvec3(a), hi = glm::dvec3(box.max) - glm::dvec3(a);
  const glm::dvec3 size = hi - lo;
  // The twelve edges: along each axis k, from the four corners with x_k = lo.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    glm::dvec3 d(0.0);
    d[k] = size[k];
    for (int corner = 0; corner < 4; ++corner) {
      glm::dvec3 e0 = lo;
      e0[i] = (corner & 1) ? hi[i] : lo[i];
      e0[j] = (corner & 2) ? hi[j] : lo[j];
      if (segmentMeetsCone(e0, d, axis, double(cone.cosAngle))) return true;
    }
  }
  return false;
}

}  // namespace passtrace::dacrt
