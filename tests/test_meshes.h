#pragma once
// Procedural meshes and seeded ray sets for tests of anything that intersects
// triangles (accelerators, CPU and GPU tracers). Everything is deterministic
// for a given seed and uses no global random state.

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace::testmesh {

// Latitude/longitude sphere: `rings` bands from pole to pole (>= 2) and
// `segments` around (>= 3); pole bands are fans, so no triangle is
// degenerate. 2 * segments * (rings - 1) triangles.
std::vector<Triangle> uvSphere(uint32_t rings, uint32_t segments, glm::vec3 center = glm::vec3(0.0f),
                               float radius = 1.0f);

// `count` random triangles with centroids uniform in `box` and vertices at
// most `maxEdge` / 2 from the centroid along each axis.
std::vector<Triangle> triangleSoup(size_t count, const Aabb& box, float maxEdge, uint64_t seed);

// The unit square [0,1]^2 split into cellsU x cellsV cells of two triangles,
// lying in the plane where coordinate `normalAxis` (0, 1, 2) equals `offset`.
// All boxes are flat along normalAxis.
std::vector<Triangle> flatGrid(uint32_t cellsU, uint32_t cellsV, int normalAxis = 2, float offset = 0.0f);

// A soup in [-1,1]^3 in which every fourth triangle is degenerate, cycling
// through: all three vertices equal, two vertices equal, collinear vertices,
// and an exact duplicate of the previous (valid) triangle.
std::vector<Triangle> degenerateMix(size_t count, uint64_t seed);

// One triangle in the z = 0 plane, spanning x, y in [-1, 1].
std::vector<Triangle> singleTriangle();

// `count` zero-area triangles whose vertices all sit at `point`.
std::vector<Triangle> pointMesh(size_t count, glm::vec3 point = glm::vec3(0.5f));

// `count` proper triangles in random orientations whose centroids are
// bit-identical (integer coordinates summing to 3 * center, which must be
// integer too), so no axis can separate them.
std::vector<Triangle> coincidentCentroids(size_t count, uint64_t seed, glm::vec3 center = glm::vec3(2.0f));

// 64 triangles in [0, 8]^3 whose uniform grid is exactly 8 x 8 x 8 cells of
// edge 1: squares lying in cell planes with corners on cell corners,
// triangles spanning the whole box, and triangles with integer vertices whose
// edges run along cell edges and faces.
std::vector<Triangle> cellBoundaryMesh();

Aabb boundsOf(std::span<const Triangle> tris);

// A named mesh, for parameterised tests.
struct NamedMesh {
  std::string name;  // identifier characters only (usable as a gtest name)
  std::vector<Triangle> tris;
};
// gtest prints parameters with this instead of their bytes.
inline void PrintTo(const NamedMesh& mesh, std::ostream* os) {
  *os << mesh.name << " (" << mesh.tris.size() << " triangles)";
}
// The standard set: sphere, soup, flat grids (z and x normal), degenerate
// mix, single triangle, coincident centroids.
std::vector<NamedMesh> standardMeshes();
// The standard set and cellBoundaries (cellBoundaryMesh), for the grid's sake.
std::vector<NamedMesh> standardMeshesAndCellBoundaries();

enum class RayKind {
  OutsideIn,     // from a shell around the bounds, aimed at random points inside
  Inside,        // from random points inside, random directions
  AxisAligned,   // direction exactly +-x, +-y or +-z, from inside or outside
  FaceParallel,  // exactly one zero direction component: parallel to two box faces
};

// `count` rays of one kind around `bounds` (expanded by 10% of its diagonal
// so flat meshes get off-plane origins). Directions are unit length except
// that AxisAligned and FaceParallel keep exact zero components. When
// finiteTMax is set, tMax is random, between 0 and about the distance
// through the bounds, so some hits fall beyond it.
std::vector<Ray> makeRays(RayKind kind, const Aabb& bounds, size_t count, uint64_t seed, bool finiteTMax = false);

// All four kinds, `countPerKind` of each, half of them with finite tMax.
std::vector<Ray> rayMix(const Aabb& bounds, size_t countPerKind, uint64_t seed);

// Long thin triangles along the xy diagonal of a 10 x 10 x 1 box: each one's
// box is nearly the whole box, so every object split overlaps completely,
// while halving them at x = 5 halves their boxes in x and y (where spatial
// splits pay).
std::vector<Triangle> longThinTriangles(size_t count, uint64_t seed);

}  // namespace passtrace::testmesh
