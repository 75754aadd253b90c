#pragma once
// The mesh and rays of the watertightness test (after pbrt-v4's Triangle
// watertight test): a closed, finely tessellated sphere whose vertices are
// jittered along their normals, and rays from inside it. Every ray from
// inside a closed mesh must hit it; one that hits nothing is a leak.
// Everything is deterministic for a given seed.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace::testmesh {

struct JitteredSphere {
  std::vector<Triangle> tris;
  std::vector<glm::vec3> vertices;          // each vertex once (the poles included)
  std::vector<glm::uvec2> edges;            // vertex index pairs, each edge once
  float minRadius = 0.0f, maxRadius = 0.0f;  // of the vertices, after jitter
};

// A latitude/longitude sphere around the origin: `rings` bands (>= 2) from
// pole to pole and `segments` around (>= 3), 2 * segments * (rings - 1)
// triangles. The vertices are built once and indexed, so neighbouring
// triangles share bit-identical corners; each vertex sits at radius
// 1 + jitter * x with x uniform in [-1, 1), its own pseudo-random amount.
JitteredSphere jitteredSphere(uint32_t rings, uint32_t segments, float jitter, uint64_t seed);

// How a ray from inside was aimed.
enum class InsideRayKind {
  Uniform,  // direction uniform on the unit sphere
  AtEdge,   // at a random point of a random edge: where two triangles meet
  AtVertex  // at a random vertex: where many triangles meet
};
inline constexpr int kInsideRayKinds = 3;

// `count` rays cycling through the kinds (ray i has kind i % 3), origins
// uniform in the ball of radius `originRadius` around the centre, unit
// directions, tMax infinite.
std::vector<Ray> insideRays(const JitteredSphere& sphere, size_t count, float originRadius, uint64_t seed);

}  // namespace passtrace::testmesh
