#pragma once
// The limits every loader holds a file to, so that a small or hostile file
// cannot make a loader allocate without bound before the memory check
// (render/memory_check.h) sees the scene.

#include <cstddef>
#include <cstdint>

namespace passtrace {

// Files read or mapped as they are: OBJ, PLY and Assimp's formats.
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{2} << 30;
// Files parsed whole in memory into a larger tree: glTF's JSON, NFF and AFF.
inline constexpr std::uintmax_t kMaxParsedFileBytes = std::uintmax_t{1} << 30;
// Instancing (one mesh under many nodes) could otherwise multiply a small
// file into any number of triangles.
inline constexpr std::size_t kMaxSceneTriangles = std::size_t{1} << 25;
// Node hierarchies are walked recursively.
inline constexpr std::size_t kMaxNodeDepth = 1024;

}  // namespace passtrace
