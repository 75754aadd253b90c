#pragma once
// "spheres": a procedurally tessellated scene of any size, for structures
// and GPU data far beyond the benchmark scenes (seed 003 asks for 100K to
// 100M triangles). A 10 x 10 field of UV spheres of varied radii on a ground
// plane, under one light; the centre sphere is a mirror. Every sphere is a
// cube sphere (six faces of n x n quads projected onto it) with the same n,
// the smallest that keeps the total at or above the requested count. Geometric normals only (no vertex normals: at millions of
// triangles the facets are sub-pixel, and 36 bytes per triangle are saved).
// Deterministic: the same triangles in the same order on every call.

#include <cstdint>

#include "scenes/scene.h"

namespace passtrace {

inline constexpr uint64_t kSphereFieldDefaultTriangles = 1'000'000;
inline constexpr uint64_t kSphereFieldMinTriangles = 1'000;
// Beyond this, triangle ids (packed indices) and 32-bit texel indices run out.
inline constexpr uint64_t kSphereFieldMaxTriangles = 400'000'000;

// The exact triangle count makeSphereField(requested) produces (at least
// `requested`; throws SceneError outside [kSphereFieldMinTriangles, kSphereFieldMaxTriangles]).
uint64_t sphereFieldTriangles(uint64_t requested);

Scene makeSphereField(uint64_t requested = kSphereFieldDefaultTriangles);

}  // namespace passtrace
