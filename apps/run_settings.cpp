#include "apps/run_settings.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace passtrace {

RunSettings toRunSettings(const Options& o) {
  RunSettings s;
  s.renderer = RendererId(o.renderer);  // the parser checked 0-3
  s.structure = o.accelerator;
  s.structureGiven = o.accelGiven;
  s.scene = o.scene;
  if (!o.bartDir.empty()) s.sceneOptions.bartDir = o.bartDir;
  if (!o.scenesDir.empty()) s.sceneOptions.realScenesDir = o.scenesDir;
  s.sceneOptions.time = o.time;
  s.sceneOptions.triangles = o.triangles;
  s.width = o.width, s.height = o.height;
  s.bounces = o.bounces, s.repeats = o.repeats, s.angles = o.angles;
  s.dumpImages = o.dumpImages;
  AccelBuildConfig& build = s.gpu.build;
  build.kayKajiya.swapProbability = 0.5f * float(o.swapChildren);
  build.gsTries = o.gsTries;
  build.gridMultiplier = o.gridMultiplier;
  build.kdMinElements = o.kdMinElements;
  build.kdMaxDepth = o.kdMaxDepth;
  build.kdStackSize = o.stackSize;
  build.triangleTest = *triangleTestByName(o.triangleTest);  // the parser accepts only valid names
  build.kdBuilder = *kdBuilderByName(o.kdBuilder);
  build.kdTermination = *kdTerminationByName(o.kdTermination);
  build.dacrtRLimit = o.dacrtRLimit, build.dacrtPLimit = o.dacrtPLimit, build.dacrtCones = o.dacrtCones;
  build.dacrtMedianSplit = o.dacrtSplit == "median";
  build.bvhBuilder = *bvhBuilderByName(o.bvhBuilder);  // the parser accepts only valid names
  build.bvh8Builder = *bvh8BuilderByName(o.bvh8Builder);
  s.gpu.loopLimit = o.loopLimit;
  s.gpu.gridKernels = o.gridKernels == "split" ? GridKernels::Split : GridKernels::Merged;
  s.gpu.maxPageTexels = o.pageTexels;
  s.gpu.stage = *parseStreamStage(o.stage);  // the parser accepts only valid names
  s.gpu.compact = o.compact == "always" ? Compaction::Always : o.compact == "on" ? Compaction::On : Compaction::Off;
  s.threads = o.threads;
  s.eye = o.eye, s.lookAt = o.lookAt, s.up = o.up, s.fov = o.fov, s.lights = o.lights;
  s.output = o.output, s.hits = o.hits, s.json = o.json, s.heatmap = o.heatmap;
  s.exportPath = o.exportPath;
  s.frames = o.frames;
  s.timeStart = o.timeStart, s.timeEnd = o.timeEnd;
  for (const auto& t : {o.timeStart, o.timeEnd})
    if (t && !std::isfinite(*t)) throw std::runtime_error("--time-start/--time-end: not a finite time");
  if ((o.timeStart || o.timeEnd) && o.frames == 0) throw std::runtime_error("--time-start and --time-end need --frames");
  s.dynamic = *dynamicStrategyByName(o.dynamic);  // the parser accepts only valid names
  s.glBackend = parseGlBackend(o.glBackend);
  s.shading.mode = *shadingModeByName(o.shading);  // the parser accepts only valid names
  s.shading.aoSamples = o.aoSamples;
  s.shading.aoDistance = o.aoDistance;
  static const std::map<std::string, BuildParam> kFlags = {
      {"--swap-children", BuildParam::SwapChildren},   {"--gs-tries", BuildParam::GsTries},
      {"--grid-multiplier", BuildParam::GridMultiplier}, {"--kd-min-elements", BuildParam::KdMinElements},
      {"--kd-max-depth", BuildParam::KdMaxDepth},     {"--grid-kernels", BuildParam::GridKernels},
      {"--loop-limit", BuildParam::LoopLimit},        {"--page-texels", BuildParam::PageTexels},
      {"--triangle-test", BuildParam::TriangleTest},  {"--stack-size", BuildParam::KdStackSize},
      {"--kd-builder", BuildParam::KdBuilder},
      {"--kd-termination", BuildParam::KdTermination},
      {"--dynamic", BuildParam::Dynamic},
      {"--dacrt-rlimit", BuildParam::DacrtRLimit},    {"--dacrt-plimit", BuildParam::DacrtPLimit},
      {"--dacrt-cones", BuildParam::DacrtCones},      {"--dacrt-split", BuildParam::DacrtSplit},
      {"--bvh-builder", BuildParam::BvhBuilder},
      {"--bvh8-builder", BuildParam::Bvh8Builder}};
  for (const std::string& flag : o.givenFlags) s.givenParams.push_back(kFlags.at(flag));
  if (o.frames == 0 && std::count(s.givenParams.begin(), s.givenParams.end(), BuildParam::Dynamic))
    throw std::runtime_error("--dynamic chooses how a --frames sequence updates its structure: it needs --frames");
  s.stats = o.stats;
  if (o.cone && !(*o.cone >= 0.0f && *o.cone < 90.0f))
    throw std::runtime_error("--cone: the half-angle must be at least 0 and below 90 degrees");
  if (!o.cone && (o.coneMaxGiven || !o.coneHits.empty()))
    throw std::runtime_error(std::string(o.coneMaxGiven ? "--cone-max" : "--cone-hits") + " needs --cone");
  s.cone = o.cone, s.coneMax = o.coneMax, s.coneHits = o.coneHits;
  s.coneSortedNodes = o.coneNodes == "sorted";
  s.coneCapacity = o.coneCapacity;
  return s;
}

Progress::Mode progressMode(const Options& o) {
  if (o.quiet) return Progress::Mode::Quiet;
  return o.progress ? Progress::Mode::Always : Progress::Mode::Auto;
}

}  // namespace passtrace
