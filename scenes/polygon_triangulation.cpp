#include "scenes/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace passtrace {
namespace {

using Point = glm::dvec2;
using Triangles = std::vector<std::array<uint32_t, 3>>;

// Lengths are compared at this fraction of the polygon's size (its bounding
// box diagonal): a file's float coordinates carry relative errors near 6e-8,
// so vertices meant to be collinear or coincident are seldom exactly so.
constexpr double kRelativeTolerance = 1e-6;
// Non-planar: a vertex farther than this fraction of the size from the plane
// through the centroid. Looser than the above: a slightly warped quad from a
// modelling tool is not worth a warning.
constexpr double kPlanarityTolerance = 1e-4;

double cross(Point a, Point b) { return a.x * b.y - a.y * b.x; }

// The polygon in its Newell plane, counter-clockwise seen from the normal.
struct Projection {
  std::vector<Point> points;
  double tolerance = 0.0;  // kRelativeTolerance times the size
  bool planar = true;
};

// How far the turn at b (from a, towards c) strays from a straight line: the
// cross product over the longer edge is the corner's distance from the line
// through its shorter edge's far end, a length comparable with tolerances.
double turn(Point a, Point b, Point c) {
  const Point e1 = b - a, e2 = c - b;
  const double longer = std::max(glm::length(e1), glm::length(e2));
  return longer > 0.0 ? cross(e1, e2) / longer : 0.0;
}

// Convex: every corner turns left or goes straight on (a turn within the
// tolerance; duplicate vertices make none), none turns back, and the
// boundary winds once (a pentagram turns left everywhere but winds twice).
bool isConvex(const Projection& poly) {
  // The corners without duplicates: consecutive vertices closer than the
  // tolerance are one.
  std::vector<Point> corners;
  for (const Point& p : poly.points)
    if (corners.empty() || glm::length(p - corners.back()) > poly.tolerance) corners.push_back(p);
  while (corners.size() > 1 && glm::length(corners.front() - corners.back()) <= poly.tolerance) corners.pop_back();
  if (corners.size() < 3) return true;  // no area: any triangulation covers nothing
  double winding = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Point a = corners[(i + corners.size() - 1) % corners.size()], b = corners[i];
    const Point c = corners[(i + 1) % corners.size()];
    const double t = turn(a, b, c);
    if (t < -poly.tolerance) return false;
    const Point e1 = b - a, e2 = c - b;
    if (t <= poly.tolerance && glm::dot(e1, e2) < 0.0) return false;  // a spike
    winding += std::atan2(cross(e1, e2), glm::dot(e1, e2));
  }
  return std::fabs(winding - 2.0 * std::numbers::pi) < 1.0;  // the winding is a multiple of 2 pi
}

// Whether two edges that share no vertex cross properly: each one's
// endpoints lie on opposite sides of the other's line, clear of the
// tolerance (touching, as a polygon with a bridge edge does, is allowed).
bool crosses(Point a, Point b, Point c, Point d, double tolerance) {
  const double ab = glm::length(b - a), cd = glm::length(d - c);
  if (ab <= tolerance || cd <= tolerance) return false;
  const double c1 = cross(b - a, c - a) / ab, d1 = cross(b - a, d - a) / ab;
  const double a1 = cross(d - c, a - c) / cd, b1 = cross(d - c, b - c) / cd;
  const auto opposite = [tolerance](double x, double y) {
    return (x > tolerance && y < -tolerance) || (x < -tolerance && y > tolerance);
  };
  return opposite(c1, d1) && opposite(a1, b1);
}

// O(n^2): only for concave polygons of at most kMaxEarClippingVertices.
bool selfIntersects(const Projection& poly) {
  const std::vector<Point>& p = poly.points;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (crosses(p[i], p[i + 1], p[j], p[(j + 1) % n], poly.tolerance)) return true;
    }
  return false;
}

// Ear clipping over a doubly linked ring of the vertices left. Appends
// n - 2 triangles in the polygon's winding; returns false when it found no
// ear in a whole round (a self-intersecting projection), having fanned the
// vertices left from the first of them in file order.
bool clipEars(const Projection& poly, Triangles& out) {
  const std::vector<Point>& p = poly.points;
  const auto n = static_cast<uint32_t>(p.size());
  std::vector<uint32_t> prev(n), next(n);
  for (uint32_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  const double tol = poly.tolerance;
  const auto coincident = [tol](Point a, Point b) { return glm::length(a - b) <= tol; };
  // Inside or on the triangle's boundary, within the tolerance.
  const auto covers = [tol](Point a, Point b, Point c, Point x) {
    const auto side = [](Point from, Point to, Point x) {
      const double len = glm::length(to - from);
      return len > 0.0 ? cross(to - from, x - from) / len : 0.0;
    };
    return side(a, b, x) >= -tol && side(b, c, x) >= -tol && side(c, a, x) >= -tol;
  };
  const auto isEar = [&](uint32_t i) {
    const Point a = p[prev[i]], b = p[i], c = p[next[i]];
    const double t = turn(a, b, c);
    // A corner on the line through its neighbours (collinear, duplicate or a
    // spike) cuts off no area, so removing it never changes the shape.
    if (std::fabs(t) <= tol) return true;
    if (t < 0.0) return false;  // reflex
    for (uint32_t r = next[next[i]]; r != prev[i]; r = next[r]) {
      const Point x = p[r];
      // A vertex repeating a corner (a polygon touching itself) does not block.
      if (coincident(x, a) || coincident(x, b) || coincident(x, c)) continue;
      if (covers(a, b, c, x)) return false;
    }
    return true;
  };

  uint32_t left = n, cursor = 0, misses = 0;
  while (left > 3 && misses < left) {
    if (!isEar(cursor)) {
      cursor = next[cursor];
      ++misses;
      continue;
    }
    const uint32_t a = prev[cursor], c = next[cursor];
    out.push_back({a, cursor, c});
    next[a] = c;
    prev[c] = a;
    cursor = c;
    --left;
    misses = 0;
  }
  // The last triangle, or the fan of what no ear could be found in.
  uint32_t first = 0;
  while (next[prev[first]] != first) ++first;  // the lowest index still linked
  for (uint32_t i = next[first]; next[i] != first; i = next[i]) out.push_back({first, i, next[i]});
  return left == 3;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> fanTriangles(std::size_t n) {
  std::vector<std::array<uint32_t, 3>> out;
  for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({0, static_cast<uint32_t>(i), static_cast<uint32_t>(i + 1)});
  return out;
}

PolygonTriangles triangulatePolygon(const std::vector<glm::vec3>& vertices) {
  const std::size_t n = vertices.size();
  PolygonTriangles result;
  if (n < 3) return result;
  if (n == 3) {
    result.triangles = fanTriangles(n);
    return result;
  }

  // In double: the cross products of float coordinates near FLT_MAX would
  // overflow in float.
  glm::dvec3 lo(vertices[0]), hi(vertices[0]), centroid(0.0);
  for (const glm::vec3& v : vertices) {
    lo = glm::min(lo, glm::dvec3(v));
    hi = glm::max(hi, glm::dvec3(v));
    centroid += glm::dvec3(v);
  }
  centroid /= static_cast<double>(n);
  const double size = glm::length(hi - lo);
  // The loaders reject non-finite vertices; whatever else, never loop on them.
  if (!(size > 0.0) || !std::isfinite(size)) {
    result.triangles = fanTriangles(n);
    return result;
  }
  const double tolerance = kRelativeTolerance * size;

  // The Newell normal: twice the area vector, whatever the winding.
  glm::dvec3 newell(0.0);
  for (std::size_t i = 0; i < n; ++i)
    newell += glm::cross(glm::dvec3(vertices[i]) - centroid, glm::dvec3(vertices[(i + 1) % n]) - centroid);
  const double area2 = glm::length(newell);
  if (area2 <= tolerance * size) {
    // No net area: a polygon on a line (or a point) covers nothing however
    // it is cut; anything else (a symmetric bow-tie) has no plane to clip in.
    const glm::dvec3 v0(vertices[0]);
    glm::dvec3 far = v0;
    for (const glm::vec3& v : vertices)
      if (glm::length(glm::dvec3(v) - v0) > glm::length(far - v0)) far = glm::dvec3(v);
    const glm::dvec3 axis = glm::normalize(far - v0);
    bool onALine = true;
    for (const glm::vec3& v : vertices)
      onALine &= glm::length(glm::cross(glm::dvec3(v) - v0, axis)) <= tolerance;
    result.triangles = fanTriangles(n);
    result.shape = onALine ? PolygonShape::Convex : PolygonShape::Irregular;
    return result;
  }

  const glm::dvec3 normal = newell / area2;
  Projection poly;
  poly.tolerance = tolerance;
  // u x w = normal, so the projection runs counter-clockwise.
  const glm::dvec3 helper = std::fabs(normal.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, normal));
  const glm::dvec3 w = glm::cross(normal, u);
  poly.points.reserve(n);
  for (const glm::vec3& v : vertices) {
    const glm::dvec3 d = glm::dvec3(v) - centroid;
    poly.points.emplace_back(glm::dot(d, u), glm::dot(d, w));
    poly.planar = poly.planar && std::fabs(glm::dot(d, normal)) <= kPlanarityTolerance * size;
  }

  if (isConvex(poly)) {
    result.triangles = fanTriangles(n);
    result.shape = poly.planar ? PolygonShape::Convex : PolygonShape::Irregular;
    return result;
  }
  if (n > kMaxEarClippingVertices) {
    result.triangles = fanTriangles(n);
    result.shape = PolygonShape::TooLarge;
    return result;
  }
  const bool simple = !selfIntersects(poly);
  const bool clipped = clipEars(poly, result.triangles);
  result.shape = poly.planar && simple && clipped ? PolygonShape::Concave : PolygonShape::Irregular;
  return result;
}

std::string PolygonWarnings::text(const std::filesystem::path& file) const {
  std::string out;
  const auto count = [](std::size_t k) { return std::to_string(k) + (k == 1 ? " polygon was " : " polygons were "); };
  if (irregular > 0)
    out += file.string() + ": " + count(irregular) +
           "non-planar or self-intersecting: triangulated by ear clipping of the projection onto the Newell plane "
           "(a fan where clipping cannot finish)\n";
  if (tooLarge > 0)
    out += file.string() + ": " + count(tooLarge) + "concave with more than " +
           std::to_string(kMaxEarClippingVertices) + " vertices: triangulated by a fan from the first vertex\n";
  return out;
}

}  // namespace passtrace
