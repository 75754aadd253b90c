#pragma once
// Resolves a scene argument: a built-in name ("cornell", "bunny") or a path
// to a scene file, dispatched by extension.

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace passtrace {

// Throws SceneError for an unknown name, an unsupported format or a bad file.
// File-loaded scenes (the bunny included) get a view and light framed on
// their bounds.
Scene loadScene(const std::string& nameOrPath);

std::vector<std::string> builtinSceneNames();

}  // namespace passtrace
