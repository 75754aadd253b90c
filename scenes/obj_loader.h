#pragma once
// Wavefront OBJ (+ .mtl) into a Scene. Polygons are fan-triangulated in file
// order; anything malformed throws SceneError naming the file and line.

#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

// The scene's name is the file's stem; its camera and light keep Scene's
// defaults (scene_registry.h frames file-loaded scenes).
Scene loadObj(const std::filesystem::path& path);

}  // namespace passtrace
