#pragma once
// Resolves a scene argument: a built-in name ("cornell", "bunny", "cows",
// "robots", "kitchen", and the procedural "spheres" of any size), a thesis scene number ("0".."4" = cows, robots,
// kitchen, bunny, cornell, the order of thesis table 1), a real benchmark
// scene's name ("conference", "sibenik", "sponza", "teapot", "dragon";
// scenes/real_scenes.h) or a path to a scene file, dispatched by extension.

#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "scenes/sphere_field.h"

namespace passtrace {

struct SceneOptions {
  // Where the BART scenes live (holding kitchen/aff/kitchen.aff and
  // robots/aff/Robot.aff). Empty: defaultBartDir().
  std::filesystem::path bartDir;
  // Where the real benchmark scenes live (--scenes-dir). Empty: defaultRealScenesDir().
  std::filesystem::path realScenesDir;
  // The time at which AFF animated transforms are evaluated (--time).
  float time = 0.0f;
  // The size of the procedural "spheres" scene (--triangles; sphere_field.h).
  uint64_t triangles = kSphereFieldDefaultTriangles;
};

// $PASSTRACE_BART_DIR, else ../shared/scenes/bart (shared_scene_dir.h); else empty.
std::filesystem::path defaultBartDir();

// Throws SceneError for an unknown name, an unsupported format, missing BART
// scenes or a bad file. OBJ scenes (the bunny included) get a view and light
// framed on their bounds; AFF/NFF and glTF scenes keep their own view and
// light where the file has them and are framed otherwise. Every scene is then
// rescaled by an exact power of two when its coordinates lie outside single
// precision's safe range (scenes/scene_scale.h; Scene::scaleExponent).
Scene loadScene(const std::string& nameOrPath, const SceneOptions& options);
Scene loadScene(const std::string& nameOrPath);  // default options

// The built-in names in thesis order: cows, robots, kitchen, bunny, cornell.
std::vector<std::string> builtinSceneNames();

// The real benchmark scenes found under `dir` (--scenes-dir; empty: the
// default places), in realScenes() order.
std::vector<std::string> availableRealSceneNames(const std::filesystem::path& dir);

// The framing that file scenes without their own view or light get: a
// 45-degree view from the front (+z), slightly above, far enough back that the
// bounding sphere fits; a light above, in front of and to the right.
CameraSpec framedCamera(const Aabb& bounds);
PointLight framedLight(const Aabb& bounds);

}  // namespace passtrace
