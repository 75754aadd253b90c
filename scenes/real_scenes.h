#pragma once
// The real benchmark scenes by name: copies of the scenes the seed documents
// measured (Papay's Sibenik and Conference, RT²'s Sponza, the cones' teapot
// and dragon, Mora's Conference), not shipped with passtrace. They are found
// like the BART scenes: --scenes-dir DIR, else $PASSTRACE_SCENES_DIR, else
// ../shared/scenes/real. Each has a standard view and light, so that results
// on "sibenik" mean the same picture on every machine (docs/scenes.md shows them).
//
// Interiors (conference, sibenik, sponza) are seen from inside, like the views
// the seeds show, with a light inside the room; their bounds' framed view
// would see the outer walls, and the framed light would leave the inside in
// shadow. They keep their one view for -n, as the thesis's Robots and Kitchen
// do. The objects (teapot, dragon) are framed on their bounds like any model
// and follow the camera path.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>

#include "scenes/scene.h"

namespace passtrace {

struct RealScene {
  std::string_view name;  // -s NAME
  std::string_view file;  // relative to the real scenes directory
  // Of the copy in ../shared/scenes/real; a file with another count loads
  // with a warning (another version of the scene is not the seeds' one).
  uint64_t triangles;
  std::string_view seeds;  // which seeds measured it, for the catalog and docs
  // In the file's units. None: framed on the bounds (scene_registry.h).
  std::optional<CameraSpec> view;
  std::optional<glm::vec3> light;
};

// conference, sibenik, sponza, teapot, dragon.
std::span<const RealScene> realScenes();
const RealScene* findRealScene(std::string_view name);

// $PASSTRACE_SCENES_DIR, else ../shared/scenes/real (shared_scene_dir.h); else empty.
std::filesystem::path defaultRealScenesDir();

// `given` (--scenes-dir) or defaultRealScenesDir() when it holds the scene's
// file; else empty.
std::filesystem::path realSceneFile(const RealScene& scene, const std::filesystem::path& given);

// The file of `scene` under `given` or the default directory; throws
// SceneError naming the three places looked in when it is not there.
std::filesystem::path requireRealSceneFile(const RealScene& scene, const std::filesystem::path& given);

// Gives a loaded file the scene's name, standard view and light (before the
// scene is rescaled, in the file's units), and warns once when its triangle
// count is not the documented copy's.
void applyRealScene(const RealScene& real, Scene& scene);

}  // namespace passtrace
