#include "scenes/scene_registry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "scenes/cornell_box.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_error.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

// The Stanford bunny as Debian's glmark2-data package ships it.
const fs::path kBunnyPath = "/usr/share/glmark2/models/bunny.obj";

// A view from the front, slightly above, far enough back that the bounding
// sphere fits the 45-degree field of view, and a light above, in front of and
// to the right of the camera.
void frame(Scene& scene) {
  const Aabb box = scene.bounds();
  const glm::vec3 centre = box.center();
  float r = 0.5f * glm::length(box.extent());
  if (!(r > 0.0f) || !std::isfinite(r)) r = 1.0f;  // a degenerate mesh still gets a usable camera
  scene.camera = CameraSpec{centre + r * glm::vec3(0.0f, 0.1f, 2.6f), centre, {0.0f, 1.0f, 0.0f}, 45.0f};
  scene.light = PointLight{centre + r * glm::vec3(1.5f, 2.5f, 2.0f), glm::vec3(1.0f)};
  scene.background = {0.1f, 0.12f, 0.16f};
  scene.ambient = 0.1f;
}

Scene loadFile(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension.empty()) throw SceneError(path, "unsupported scene format (no file extension)");
  if (extension != ".obj") throw SceneError(path, "unsupported scene format '" + extension + "'");
  Scene scene = loadObj(path);
  frame(scene);
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"cornell", "bunny"}; }

Scene loadScene(const std::string& nameOrPath) {
  if (nameOrPath == "cornell") return makeCornellBox();
  if (nameOrPath == "bunny") {
    std::error_code ignored;
    if (!fs::exists(kBunnyPath, ignored))
      throw SceneError("bunny", kBunnyPath.string() + " not found (install glmark2-data)");
    Scene scene = loadFile(kBunnyPath);
    scene.name = "bunny";
    return scene;
  }
  // A missing file with an extension is still taken as a path, so that a
  // typo in "scenes/room.obj" reports "cannot open" rather than an unknown name.
  const fs::path path = nameOrPath;
  std::error_code ignored;
  if (fs::exists(path, ignored) || path.has_extension()) return loadFile(path);
  throw SceneError("unknown scene '" + nameOrPath + "' (expected cornell, bunny or a file path)");
}

}  // namespace passtrace
