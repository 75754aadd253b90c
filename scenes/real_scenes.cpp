#include "scenes/real_scenes.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>
#include <system_error>

#include "scenes/scene_error.h"
#include "scenes/shared_scene_dir.h"

namespace passtrace {

namespace fs = std::filesystem;

namespace {

// The interiors' views look down the room's long axis from near one end, at
// about eye height, as the seeds' pictures of them do; each light hangs under
// the ceiling between the eye and the room's middle, so that what the view
// sees is lit and the columns, chairs and arches still cast shadows.
const RealScene kRealScenes[] = {
    {"conference", "conference/conference.ply", 331'179, "seed 003 (Papay), seed 001 (Mora), seed 000 Table 2",
     CameraSpec{{1500.0f, 450.0f, 500.0f}, {0.0f, 150.0f, -300.0f}, {0.0f, 1.0f, 0.0f}, 50.0f},
     glm::vec3(900.0f, 600.0f, 0.0f)},
    {"sibenik", "sibenik/sibenik.ply", 75'284, "seed 003 (Papay), seed 000 Table 2",
     CameraSpec{{-17.0f, -11.0f, 0.0f}, {5.0f, -9.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 55.0f},
     glm::vec3(-12.0f, -4.0f, 0.0f)},
    {"sponza", "sponza/sponza.3DS", 69'063, "seed 002 (RT2), seed 003 (Papay), seed 000 Table 2",
     CameraSpec{{13.0f, 2.5f, 0.0f}, {-5.0f, 5.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 55.0f},
     glm::vec3(8.0f, 8.0f, 0.0f)},
    {"teapot", "teapot/teapot.obj", 6'320, "seed 000 Table 1", std::nullopt, std::nullopt},
    {"dragon", "dragon/dragon_vrip.ply", 871'414, "seed 000 Table 1", std::nullopt, std::nullopt},
};

bool holds(const fs::path& dir, const RealScene& scene) {
  std::error_code ec;
  return !dir.empty() && fs::is_regular_file(dir / scene.file, ec);
}

}  // namespace

std::span<const RealScene> realScenes() { return kRealScenes; }

const RealScene* findRealScene(std::string_view name) {
  const auto* it = std::find_if(std::begin(kRealScenes), std::end(kRealScenes),
                                [&](const RealScene& s) { return s.name == name; });
  return it == std::end(kRealScenes) ? nullptr : it;
}

fs::path defaultRealScenesDir() { return findSharedSceneDir("PASSTRACE_SCENES_DIR", "real"); }

fs::path realSceneFile(const RealScene& scene, const fs::path& given) {
  const fs::path dir = given.empty() ? defaultRealScenesDir() : given;
  return holds(dir, scene) ? dir / scene.file : fs::path();
}

fs::path requireRealSceneFile(const RealScene& scene, const fs::path& given) {
  if (fs::path file = realSceneFile(scene, given); !file.empty()) return file;
  const std::string name(scene.name), file(scene.file);
  if (!given.empty())
    throw SceneError(name + ": " + (given / file).string() + " not found (--scenes-dir " + given.string() + ")");
  if (const fs::path dir = defaultRealScenesDir(); !dir.empty())
    throw SceneError(name + ": " + (dir / file).string() + " not found (the real scenes directory, from " +
                     (std::getenv("PASSTRACE_SCENES_DIR") ? "$PASSTRACE_SCENES_DIR" : "../shared/scenes/real") + ")");
  throw SceneError(name + ": the real benchmark scenes were not found: give --scenes-dir DIR, set "
                          "$PASSTRACE_SCENES_DIR, or put them in ../shared/scenes/real (beside the current directory "
                          "or the executable's), holding " + file);
}

void applyRealScene(const RealScene& real, Scene& scene) {
  scene.name = std::string(real.name);
  if (scene.triangles.size() != real.triangles)
    std::cerr << "passtrace: warning: " << real.name << ": " << scene.triangles.size()
              << " triangles, not the documented copy's " << real.triangles
              << " (another version of the scene: results are not comparable with the reports')\n";
  if (real.view) {
    scene.camera = *real.view;
    scene.fixedView = true;
  }
  if (real.light) {
    scene.light = PointLight{*real.light, glm::vec3(1.0f)};
    scene.lights.clear();
    scene.lightIsDefault = false;
  }
}

}  // namespace passtrace
