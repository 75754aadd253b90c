#include "scenes/scene_registry.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "scenes/aff_loader.h"
#include "scenes/assimp_loader.h"
#include "scenes/cornell_box.h"
#include "scenes/cows_scene.h"
#include "scenes/file_extension.h"
#include "scenes/gltf_loader.h"
#include "scenes/obj_loader.h"
#include "scenes/off_reader.h"
#include "scenes/ply_reader.h"
#include "scenes/real_scenes.h"
#include "scenes/scene_error.h"
#include "scenes/scene_scale.h"
#include "scenes/shared_scene_dir.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

// The Stanford bunny as Debian's glmark2-data package ships it.
const fs::path kBunnyPath = "/usr/share/glmark2/models/bunny.obj";

// The thesis's scene numbers (-s 0..4), table 1's order.
const std::array<const char*, 5> kThesisOrder = {"cows", "robots", "kitchen", "bunny", "cornell"};

// Centre and radius in double: in float the extent of a scene near FLT_MAX
// overflows and the squared extent of a tiny one underflows to 0.
glm::dvec3 centreOf(const Aabb& box) {
  return box.empty() ? glm::dvec3(0.0) : 0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max));
}

double radiusOf(const Aabb& box) {
  if (box.empty()) return 1.0;
  const double r = 0.5 * glm::length(glm::dvec3(box.max) - glm::dvec3(box.min));
  if (r > 0.0) return r;
  // All in one point: a view from a little away, relative to its distance
  // from the origin so that the eye does not round onto the point.
  const glm::dvec3 c = glm::abs(centreOf(box));
  return std::max(1.0, 1e-3 * std::max({c.x, c.y, c.z}));
}

// May overflow to infinity near FLT_MAX; loadScene then frames again after
// rescaling (scene_scale.h).
glm::vec3 framedPoint(const Aabb& box, const glm::dvec3& offset) {
  return glm::vec3(centreOf(box) + radiusOf(box) * offset);
}

// A view and light framed on the bounds, and a dark blue-grey background.
void frame(Scene& scene) {
  const Aabb box = scene.bounds();
  scene.camera = framedCamera(box);
  scene.light = framedLight(box);
  scene.lightIsDefault = true;
  scene.background = {0.1f, 0.12f, 0.16f};
  scene.ambient = 0.1f;
}

Scene loadFile(const fs::path& path, const SceneOptions& options) {
  const std::string extension = lowerExtension(path);
  if (extension.empty()) throw SceneError(path, "unsupported scene format (no file extension)");
  if (extension == ".aff" || extension == ".nff") return loadAff(path, options.time);
  if (extension == ".gltf" || extension == ".glb") return loadGltf(path, options.time);
  const std::vector<std::string>& viaAssimp = assimpExtensions();
  if (std::find(viaAssimp.begin(), viaAssimp.end(), extension) != viaAssimp.end()) return loadWithAssimp(path);
  if (extension != ".obj" && extension != ".ply" && extension != ".off")
    throw SceneError(path, "unsupported scene format '" + extension + "'");
  Scene scene = extension == ".ply" ? loadPly(path) : extension == ".off" ? loadOff(path) : loadObj(path);
  frame(scene);
  return scene;
}

// A BART scene: DIR/<scene>/aff/<file>.
Scene loadBart(const std::string& name, const fs::path& relative, const SceneOptions& options) {
  fs::path dir = options.bartDir.empty() ? defaultBartDir() : options.bartDir;
  std::error_code ec;
  if (dir.empty())
    throw SceneError(name + ": the BART scenes were not found (looked for ../shared/scenes/bart next to the current "
                            "directory and the executable); set PASSTRACE_BART_DIR to the directory holding "
                            "kitchen/ and robots/");
  const fs::path file = dir / relative;
  if (!fs::exists(file, ec))
    throw SceneError(name + ": " + file.string() + " not found (the BART directory is " + dir.string() +
                     "; set PASSTRACE_BART_DIR to the directory holding kitchen/ and robots/)");
  Scene scene = loadAff(file, options.time);
  scene.fixedView = true;
  scene.name = name;
  return scene;
}

}  // namespace

CameraSpec framedCamera(const Aabb& box) {
  return CameraSpec{framedPoint(box, {0.0, 0.1, 2.6}), glm::vec3(centreOf(box)), {0.0f, 1.0f, 0.0f}, 45.0f};
}

PointLight framedLight(const Aabb& box) { return PointLight{framedPoint(box, {1.5, 2.5, 2.0}), glm::vec3(1.0f)}; }

fs::path defaultBartDir() { return findSharedSceneDir("PASSTRACE_BART_DIR", "bart"); }

std::vector<std::string> availableRealSceneNames(const fs::path& dir) {
  std::vector<std::string> names;
  for (const RealScene& s : realScenes())
    if (!realSceneFile(s, dir).empty()) names.emplace_back(s.name);
  return names;
}

namespace {
Scene loadUnscaled(const std::string& nameOrPath, const SceneOptions& options);
void bringIntoSafeRange(Scene& scene, const std::string& source);
}  // namespace

std::vector<std::string> builtinSceneNames() { return {kThesisOrder.begin(), kThesisOrder.end()}; }

Scene loadScene(const std::string& nameOrPath) { return loadScene(nameOrPath, SceneOptions{}); }

Scene loadScene(const std::string& nameOrPath, const SceneOptions& options) {
  Scene scene = loadUnscaled(nameOrPath, options);
  bringIntoSafeRange(scene, nameOrPath);
  return scene;
}

namespace {

Scene loadUnscaled(const std::string& nameOrPath, const SceneOptions& options) {
  if (nameOrPath.size() == 1 && nameOrPath[0] >= '0' && nameOrPath[0] <= '4')
    return loadScene(kThesisOrder[static_cast<std::size_t>(nameOrPath[0] - '0')], options);
  if (nameOrPath == "cornell") {
    Scene scene = makeCornellBox();
    scene.fixedView = true;
    return scene;
  }
  if (nameOrPath == "cows") return makeCowsScene();
  if (nameOrPath == "spheres") return makeSphereField(options.triangles);
  if (nameOrPath == "robots") return loadBart("robots", fs::path("robots") / "aff" / "Robot.aff", options);
  if (nameOrPath == "kitchen") return loadBart("kitchen", fs::path("kitchen") / "aff" / "kitchen.aff", options);
  if (const RealScene* real = findRealScene(nameOrPath)) {
    Scene scene = loadFile(requireRealSceneFile(*real, options.realScenesDir), options);
    applyRealScene(*real, scene);
    return scene;
  }
  if (nameOrPath == "bunny") {
    std::error_code ignored;
    if (!fs::exists(kBunnyPath, ignored))
      throw SceneError("bunny", kBunnyPath.string() + " not found (install glmark2-data)");
    Scene scene = loadFile(kBunnyPath, options);
    scene.name = "bunny";
    return scene;
  }
  // A missing file with an extension is still taken as a path, so that a
  // typo in "scenes/room.obj" reports "cannot open" rather than an unknown name.
  const fs::path path = nameOrPath;
  std::error_code ignored;
  if (fs::exists(path, ignored) || path.has_extension()) return loadFile(path, options);
  throw SceneError("unknown scene '" + nameOrPath +
                   "' (expected cows, robots, kitchen, bunny, cornell, spheres, 0-4, conference, sibenik, sponza, "
                   "teapot, dragon or a file path)");
}

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Rescales by 2^k (scene_scale.h). A view or light that is not finite after
// it is framed again on the rescaled bounds: silently where the framing
// itself overflowed (near FLT_MAX), with a warning where the file's own view
// or light lies too far from tiny geometry.
void bringIntoSafeRange(Scene& scene, const std::string& source) {
  const Aabb before = scene.bounds();
  const float largest = before.empty() ? 0.0f
                                       : std::max({std::fabs(before.min.x), std::fabs(before.min.y),
                                                   std::fabs(before.min.z), std::fabs(before.max.x),
                                                   std::fabs(before.max.y), std::fabs(before.max.z)});
  if (largest > 0.0f && largest < std::numeric_limits<float>::min())
    std::cerr << "passtrace: warning: " << source << ": every coordinate is subnormal (largest " << largest
              << "): vertices keep fewer than 24 bits of precision\n";
  const bool viewWasFinite = isFinite(scene.camera.eye) && isFinite(scene.camera.lookAt);
  const bool lightWasFinite = isFinite(scene.light.position);
  const int k = normalizeSceneScale(scene);
  const CameraSpec& c = scene.camera;
  const bool reframeView = !isFinite(c.eye) || !isFinite(c.lookAt) || c.eye == c.lookAt;
  const bool reframeLight = !isFinite(scene.light.position);
  if ((reframeView && viewWasFinite) || (reframeLight && lightWasFinite))
    std::cerr << "passtrace: warning: " << source << ": the file's " << (reframeView && viewWasFinite ? "view" : "light")
              << " does not fit in single precision after rescaling the scene by 2^" << k
              << "; it is framed on the scene's bounds\n";
  if (reframeView) {
    const CameraSpec framed = framedCamera(scene.bounds());
    scene.camera.eye = framed.eye;
    scene.camera.lookAt = framed.lookAt;
  }
  if (reframeLight) scene.light.position = framedLight(scene.bounds()).position;
  // Whitted's separate lights stay only while every one is finite; else the one framed light.
  if (!std::all_of(scene.lights.begin(), scene.lights.end(), [](const PointLight& l) { return isFinite(l.position); }))
    scene.lights.clear();
}

}  // namespace

}  // namespace passtrace
