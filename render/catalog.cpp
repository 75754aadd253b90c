#include "render/catalog.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "accel/registry.h"
#include "passtrace_version.h"
#include "scenes/real_scenes.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

std::vector<std::string> rendererNames(const Structure& s) {
  std::vector<std::string> names;
  for (RendererId r : kRenderers)
    if (s.runsOn(r)) names.emplace_back(rendererName(r));
  return names;
}

// The names with thesis numbers; the procedural scene and the real scenes
// (those found) have none.
std::vector<std::pair<std::string, nlohmann::json>> sceneRows(const std::filesystem::path& realScenesDir) {
  std::vector<std::pair<std::string, nlohmann::json>> rows;
  const std::vector<std::string> builtin = builtinSceneNames();
  for (size_t i = 0; i < builtin.size(); ++i) rows.emplace_back(builtin[i], int(i));
  rows.emplace_back("spheres", nullptr);
  for (const std::string& name : availableRealSceneNames(realScenesDir)) rows.emplace_back(name, nullptr);
  return rows;
}

// How the text catalog describes a scene without a thesis number.
std::string unnumberedNote(const std::string& name) {
  if (name == "spheres") return " (procedural, --triangles)";
  const RealScene* real = findRealScene(name);
  return real ? " (" + std::to_string(real->triangles) + " triangles; " + std::string(real->seeds) + ")" : "";
}

}  // namespace

nlohmann::json catalogJson(const std::filesystem::path& realScenesDir) {
  nlohmann::json renderers = nlohmann::json::array();
  for (RendererId r : kRenderers) renderers.push_back({{"name", rendererName(r)}, {"id", int(r)}});
  nlohmann::json accelerators = nlohmann::json::array();
  for (const Structure& s : structures()) {
    nlohmann::json featured = nlohmann::json::array();
    for (const Featured& f : s.featured)
      featured.push_back({{"report", reportName(f.report)}, {"renderer", rendererName(f.renderer)}});
    accelerators.push_back({{"name", s.name},
                            {"renderers", rendererNames(s)},
                            {"number", s.number ? nlohmann::json(*s.number) : nlohmann::json(nullptr)},
                            {"cpu_ray_groups", s.runsOn(RendererId::Cpu) ? nlohmann::json(rayGroupingName(s.cpuRayGrouping))
                                                                          : nlohmann::json(nullptr)},
                            {"featured", featured},
                            {"description", s.description}});
  }
  nlohmann::json scenes = nlohmann::json::array();
  for (const auto& [name, number] : sceneRows(realScenesDir)) scenes.push_back({{"name", name}, {"number", number}});
  return {{"version", kVersion}, {"renderers", renderers}, {"accelerators", accelerators}, {"scenes", scenes}};
}

std::string catalogJsonText(const std::filesystem::path& realScenesDir) {
  return catalogJson(realScenesDir).dump(2) + "\n";
}

std::string catalogText(const std::filesystem::path& realScenesDir) {
  std::string text = "Renderers (-r):\n";
  for (RendererId r : kRenderers) {
    // A ray tracer with no structure was left out of this build (Embree without libembree-dev).
    const bool built = r == RendererId::OpenGl ||
                       std::any_of(structures().begin(), structures().end(), [r](const Structure& s) { return s.runsOn(r); });
    text += "  " + std::to_string(int(r)) + " " + std::string(rendererName(r)) + ": " +
            std::string(rendererTitle(r)) + (built ? "" : " (not in this build)") + "\n";
  }
  size_t width = 0;
  for (const Structure& s : structures()) width = std::max(width, s.name.size());
  text += "Structures (-a NAME, or the thesis number in the renderer's column):\n";
  for (const Structure& s : structures()) {
    std::string renderers;
    for (const std::string& r : rendererNames(s)) renderers += (renderers.empty() ? "" : ",") + r;
    std::string number = "  ";
    if (s.number) {
      number = std::to_string(*s.number);
      if (!s.numberedOn.has(RendererId::Cpu) || !s.numberedOn.has(RendererId::Gpu))
        number += s.numberedOn.has(RendererId::Gpu) ? " on gpu" : " on cpu";
    }
    number.resize(9, ' ');
    std::string name(s.name);
    name.resize(width, ' ');
    std::string on = "[" + renderers + "]";
    on.resize(13, ' ');
    text += "  " + number + name + "  " + on + " " + std::string(s.description) + "\n";
  }
  // Each parameter with its default and the structures that read it; a given
  // flag the chosen structure does not read is a warning.
  text += "Build parameters (default; read by):\n";
  for (BuildParam p : kBuildParams) {
    std::string flag(buildParamFlag(p)), value = buildParamDefault(p), readers;
    size_t everywhere = 0, rayTracing = 0;  // rows reading it on all their renderers; rows but Embree's
    for (const Structure& s : structures()) {
      std::string on;
      bool all = true;
      for (RendererId r : kRenderers) {
        if (!s.runsOn(r)) continue;
        const std::vector<BuildParam> reads = s.readsOn(r);
        if (std::find(reads.begin(), reads.end(), p) == reads.end()) {
          all = false;
          continue;
        }
        if (!on.empty()) on += ',';
        on += rendererName(r);
      }
      if (!s.runsOn(RendererId::Embree)) ++rayTracing;
      if (on.empty()) continue;
      everywhere += all;
      if (!readers.empty()) readers += ", ";
      readers += s.name;
      if (!all) readers += " on " + on;
    }
    if (everywhere == rayTracing && readers.find(" on ") == std::string::npos) readers = "every structure but embree";
    flag.resize(22, ' ');
    value.resize(24, ' ');
    text += "  " + flag + value + readers + "\n";
  }
  text += "Scenes (-s NAME or number, or a .obj/.aff/.nff/.gltf/.glb file, or through Assimp a "
          ".ply/.stl/.off/.dae/.3ds/.x/.fbx file; the real scenes where --scenes-dir, $PASSTRACE_SCENES_DIR "
          "or ../shared/scenes/real has them):\n";
  for (const auto& [name, number] : sceneRows(realScenesDir))
    text += "  " + (number.is_null() ? std::string(" ") : std::to_string(int(number))) + " " + name +
            unnumberedNote(name) + "\n";
  return text;
}

}  // namespace passtrace
