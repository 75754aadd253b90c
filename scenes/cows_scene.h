#pragma once
// A Cows-like scene (thesis figure 24a; the original is not available),
// generated in code with the same properties: a recursive tree in the spirit
// of Haines' SPD "tree" (a few large trunk triangles at the bottom, thousands
// of small ones in the branches and leaves), three dense meshes on the ground
// (the Stanford bunny from glmark2-data, decimated by vertex clustering and
// scaled; a tessellated sphere blob when the file is absent), a ground plane
// and a mirror back plane, the benchmark's only specular surface.
// Deterministic: the same triangles in the same order on every call.

#include <cstddef>

#include "scenes/scene.h"

namespace passtrace {

// Triangle counts (pinned by tests/cows_scene_test.cpp).
inline constexpr std::size_t kCowsTriangles = 30274;          // with the bunny
inline constexpr std::size_t kCowsTrianglesNoBunny = 25000;   // the sphere fallback

// Named "cows". Vertex normals everywhere; materials: 0 ground, 1 mirror back
// plane, 2 bark, 3 leaves, 4 bunnies.
Scene makeCowsScene();

}  // namespace passtrace
