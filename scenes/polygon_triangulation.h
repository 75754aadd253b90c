#pragma once
// A polygon's vertices (in file order) to triangles, as index triples into
// them. Every polygon of n >= 3 vertices gives exactly n - 2 triangles, so a
// file's triangle count and ids do not depend on the polygons' shapes; the
// triangles keep the polygon's winding and come in a deterministic order.
//
// The rule, by shape (measured in the plane of the Newell normal, with
// tolerances relative to the polygon's size):
//  - convex (every turn the same way, winding once; collinear and duplicate
//    vertices allowed): the fan (0, i, i + 1), i = 1..n-2, as passtrace has
//    always built it;
//  - concave, planar and simple: ear clipping in the polygon's plane;
//    collinear and duplicate vertices make zero-area ears, clipped like
//    any other;
//  - non-planar or self-intersecting: the same two rules applied to the
//    polygon's projection onto its Newell plane (the fan when the projection
//    is convex, ear clipping otherwise), and the fan over the vertices left
//    when clipping finds no ear; a polygon whose Newell normal vanishes (a
//    symmetric bow-tie) is fanned. Such polygons are flagged Irregular, for
//    the loaders' counted warning (polygonWarning);
//  - concave with more than kMaxEarClippingVertices vertices: the fan, also
//    flagged (ear clipping costs O(n^2) and more).

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace passtrace {

inline constexpr std::size_t kMaxEarClippingVertices = 4096;

enum class PolygonShape {
  Convex,     // fanned (also a triangle, and a polygon with no area)
  Concave,    // planar and simple: ear-clipped
  Irregular,  // non-planar or self-intersecting: the rule above
  TooLarge,   // concave beyond kMaxEarClippingVertices: fanned
};

struct PolygonTriangles {
  std::vector<std::array<uint32_t, 3>> triangles;  // n - 2 (none for n < 3)
  PolygonShape shape = PolygonShape::Convex;
};

PolygonTriangles triangulatePolygon(const std::vector<glm::vec3>& vertices);
// The fan (0, i, i + 1), i = 1..n-2.
std::vector<std::array<uint32_t, 3>> fanTriangles(std::size_t n);

// The polygons of one file that the rule could not triangulate faithfully,
// counted so that the loader warns once per file, not once per polygon.
struct PolygonWarnings {
  std::size_t irregular = 0;
  std::size_t tooLarge = 0;

  void count(PolygonShape shape) {
    irregular += shape == PolygonShape::Irregular;
    tooLarge += shape == PolygonShape::TooLarge;
  }
  // One line per kind counted, "FILE: N polygons were ...\n"; empty if none.
  std::string text(const std::filesystem::path& file) const;
};

}  // namespace passtrace
