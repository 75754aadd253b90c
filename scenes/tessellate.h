#pragma once
// Curved NFF primitives and polygons to triangles, with vertex normals.
//
// Counting rules (they fix the triangle count of any NFF/AFF file):
//  - a polygon or patch with n vertices: n - 2 triangles, degenerate ones
//    kept; convex ones the fan (v0, v[i], v[i+1]), i = 1..n-2, others as
//    polygon_triangulation.h says;
//  - a sphere: kSphereSlices around by kSphereStacks from pole to pole, the
//    two polar rings fans, every other band quads split in two:
//    2 * slices * (stacks - 1) triangles (224);
//  - a cone or cylinder: the open side only (NFF cones have no caps),
//    kConeSlices quads split in two: 2 * slices triangles (32), or one
//    triangle per slice when either radius is 0 (16).

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "scenes/polygon_triangulation.h"

namespace passtrace {

inline constexpr int kSphereSlices = 16;
inline constexpr int kSphereStacks = 8;
inline constexpr int kConeSlices = 16;

struct TriangleList {
  std::vector<Triangle> triangles;
  std::vector<std::array<glm::vec3, 3>> normals;  // one entry per triangle
};

void tessellateSphere(const glm::vec3& centre, float radius, TriangleList& out, int slices = kSphereSlices,
                      int stacks = kSphereStacks);
void tessellateCone(const glm::vec3& base, float baseRadius, const glm::vec3& apex, float apexRadius,
                    TriangleList& out, int slices = kConeSlices);
// Appends a polygon's triangles (triangulatePolygon) and returns its shape;
// `normals` is empty or one per vertex, and follow their vertices. Without
// normals every corner gets the polygon's geometric normal (from the first
// triangle with non-zero area, or +z when all are degenerate).
PolygonShape appendPolygon(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                           TriangleList& out);
// The same for a polygon known to be convex (the built-in scenes' quads):
// always the fan.
void triangulateFan(const std::vector<glm::vec3>& vertices, const std::vector<glm::vec3>& normals,
                    TriangleList& out);

// The unit normal of a triangle, or `fallback` when it has no area.
glm::vec3 faceNormal(const Triangle& t, const glm::vec3& fallback = {0.0f, 0.0f, 1.0f});

}  // namespace passtrace
