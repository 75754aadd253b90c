#pragma once
// Wavefront OBJ (+ .mtl) into a Scene. Faces in file order, each one's n - 2
// triangles consecutive, triangulated as polygon_triangulation.h says
// (convex: the fan from the first corner; concave: ear clipping), with one
// warning line on stderr counting the non-planar and self-intersecting ones;
// anything malformed throws SceneError naming the file and line.

#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

// The scene's name is the file's stem; its camera and light keep Scene's
// defaults (scene_registry.h frames file-loaded scenes).
Scene loadObj(const std::filesystem::path& path);

}  // namespace passtrace
