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
#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

// Triangle counts (pinned by tests/unit/cows_scene_test.cpp).
// 4 planes + tree (16 trunk + 1092 * 12 branch + 729 * 8 leaf triangles) +
// 3 meshes (3,945 each from the bunny, 1,520 each for the fallback blob).
inline constexpr std::size_t kCowsTriangles = 30791;         // with the bunny
inline constexpr std::size_t kCowsTrianglesNoBunny = 23516;  // the blob fallback

// Named "cows" either way. Vertex normals everywhere; materials: 0 ground, 1 mirror back
// plane, 2 bark, 3 leaves, 4 bunnies.
// `bunnyPath` is the OBJ to decimate (a missing file selects the fallback).
Scene makeCowsScene(const std::filesystem::path& bunnyPath = "/usr/share/glmark2/models/bunny.obj");

}  // namespace passtrace
