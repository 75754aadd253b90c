#pragma once
// One passtrace run: scene -> structure -> renderer -> report. Loads the
// scene, checks the memory, builds the structure named by the registry,
// renders every camera angle `repeats` times keeping the fastest (thesis
// 10.1.1), writes the outputs, and returns the RunReport. apps/ only parses
// the command line into these settings.

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "accel/kd/kd_dynamic.h"
#include "accel/registry.h"
#include "render/progress.h"
#include "render/run_report.h"
#include "render/shading_config.h"
#include "scenes/scene_registry.h"
#include "stream/gl_context.h"

namespace passtrace {

struct RunSettings {
  RendererId renderer = RendererId::Gpu;
  std::string structure = "0";      // -a: a name or the thesis number in the renderer's column
  bool structureGiven = false;      // -a was on the command line
  std::string scene = "bunny";      // a built-in name or number, "spheres", or a file
  SceneOptions sceneOptions;
  int width = 512, height = 512;
  int bounces = 3;                  // traces per path, primary and shadow rays included
  int repeats = 1;                  // per angle; the fastest is reported
  int angles = 1;                   // camera-path angles
  bool dumpImages = false;          // every angle's image as NAME_k.EXT
  GpuTraversalConfig gpu;           // gpu.build: every structure's build parameters
  unsigned threads = 0;             // CPU renderers; 0 = all cores
  std::optional<glm::vec3> eye, lookAt, up;  // in the file's units
  std::optional<float> fov;
  std::vector<glm::vec3> lights;             // --light, in the file's units; empty: the scene's (scenes/scene_lights.h)
  std::string output, hits, json, heatmap;   // empty: not written
  GlBackend glBackend = GlBackend::Auto;
  std::vector<BuildParam> givenParams;  // flags given; those the structure ignores are warned of
  bool stats = false;                   // the summary's structure and per-ray lines
  std::string exportPath;               // --export: write the scene (scenes/scene_export.h), render nothing
  int frames = 0;                       // --frames N: a sequence over the animation; 0 = one frame at --time
  std::optional<float> timeStart, timeEnd;  // --time-start/--time-end; default: the scene's animation range
  DynamicStrategy dynamic = DynamicStrategy::Rebuild;  // --dynamic: how --frames updates a kd row's structure
  ShadingConfig shading;                // --shading, --ao-samples, --ao-distance
  std::optional<float> cone;  // --cone DEG: cone queries instead of rays (render/cone_session.h)
  uint32_t coneMax = 0;       // --cone-max: 0 = every triangle met
  std::string coneHits;       // --cone-hits FILE.exr
  bool coneSortedNodes = false;  // --cone-nodes sorted (ConeQueryConfig::sortedNodes)
  uint32_t coneCapacity = 1024;  // --cone-capacity: -r 2's per-cone list (GpuConeConfig::capacity)
};

// Throws std::runtime_error (or a subclass) with a one-line message on any
// bad input or failure. The outputs appear together once the whole run has
// succeeded, or none of them (render/output_files.h).
RunReport runSession(const RunSettings& settings, Progress& progress);

}  // namespace passtrace
