#include "apps/run_render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/memory_check.h"
#include "accel/cpu_accelerator.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/stream_mirror_accelerators.h"
#include "render/atomic_file.h"
#include "render/camera.h"
#include "render/camera_path.h"
#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"
#include "render/heatmap.h"
#include "render/image_output.h"
#include "render/preview_renderer.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"
#include "stream/gl_context.h"
#include "stream/inout_stream.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

const char* kRendererNames[] = {"opengl", "cpu", "gpu", "embree"};

std::vector<CameraSpec> cameraViews(const Scene& scene, const Options& o) {
  CameraSpec base = scene.camera;
  if (o.fov) base.fovDegrees = *o.fov;
  std::vector<CameraSpec> views;
  if (o.angles == 1 || scene.fixedView) {
    views.assign(size_t(o.angles), base);
  } else {
    Scene pathScene = scene;
    pathScene.camera = base;
    for (int k = 0; k < o.angles; ++k) views.push_back(cameraPathView(pathScene, k, o.angles));
  }
  // The command line speaks the file's units; the scene may be rescaled by 2^k.
  const auto toScene = [&](const char* option, const glm::vec3& p) {
    const glm::vec3 scaled = scaleByPowerOfTwo(p, scene.scaleExponent);
    if (!std::isfinite(scaled.x) || !std::isfinite(scaled.y) || !std::isfinite(scaled.z))
      throw std::runtime_error(std::string(option) + ": too far from the scene for single precision (the scene is "
                               "rescaled by 2^" + std::to_string(scene.scaleExponent) + ")");
    return scaled;
  };
  for (CameraSpec& v : views) {
    if (o.eye) v.eye = toScene("--eye", *o.eye);
    if (o.lookAt) v.lookAt = toScene("--look-at", *o.lookAt);
    if (o.up) v.up = *o.up;
  }
  return views;
}

// "out.png", k -> "out_k.png"
fs::path numberedPath(const fs::path& path, int k) {
  return path.parent_path() / (path.stem().string() + "_" + std::to_string(k) + path.extension().string());
}

void checkOutputs(const Options& o) {
  if (!o.output.empty()) {
    checkWritable(o.output);
    checkImageFormat(o.output);
  }
  if (!o.hits.empty()) {
    checkWritable(o.hits);
    if (fs::path(o.hits).extension() != ".exr") throw std::runtime_error(o.hits + ": hit buffers are OpenEXR (.exr) files");
  }
  if (!o.json.empty()) checkWritable(o.json);
  if (!o.heatmap.empty()) {
    checkWritable(o.heatmap);
    checkImageFormat(o.heatmap);
  }
}

// Renders one view with whichever renderer was chosen.
using RenderFn = std::function<FrameResult(const CameraSpec&, bool captureHits)>;

// The CPU accelerator named by -a: a Table 4 number or name, or one of the
// GPU kernels' algorithms run on the CPU.
std::unique_ptr<CpuAccelerator> makeCpuAcceleratorFor(const std::string& name, const Scene& scene,
                                                      const AccelBuildConfig& build) {
  if (const auto mirror = streamMirrorByName(name)) return makeStreamMirrorAccelerator(*mirror, scene.triangles, build);
  return makeCpuAccelerator(acceleratorNumber(name), scene.triangles, build);
}

// In double: the cross product of tiny edges underflows in float.
bool hasArea(const Triangle& t) {
  const glm::dvec3 v0(t.v0);
  const glm::dvec3 n = glm::cross(glm::dvec3(t.v1) - v0, glm::dvec3(t.v2) - v0);
  return n != glm::dvec3(0.0);
}

}  // namespace

void runPassTrace(const Options& o) {
  // Reject an unknown accelerator name before loading anything.
  const int accelerator = o.renderer == 3   ? -1
                          : o.renderer == 2 ? gpuAcceleratorNumber(o.accelerator)
                          : streamMirrorByName(o.accelerator) ? -1
                                                              : acceleratorNumber(o.accelerator);
  if ((o.renderer == 1 || o.renderer == 3) && (long long)o.width * o.height > kMaxCpuPixels)
    throw std::runtime_error("image " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " is too large for the CPU renderer (at most 16384x16384 pixels)");
  checkOutputs(o);
  // The GL first: its limits on the image size are known before anything is built.
  std::unique_ptr<GlContext> gl;
  if (o.renderer == 0 || o.renderer == 2) {
    std::string notices;
    gl = GlContext::create(parseGlBackend(o.glBackend), &notices);
    if (!notices.empty() && !o.quiet) std::cerr << "passtrace: " << notices;
    InOutStream::checkSize(o.width, o.height);
  }
  SceneOptions sceneOptions;
  if (!o.bartDir.empty()) sceneOptions.bartDir = o.bartDir;
  sceneOptions.time = o.time;
  sceneOptions.triangles = o.triangles;
  // Say so before trying: the procedural scene's size is known before it is
  // made, a file's once it is read.
  const std::string structure = o.renderer == 3   ? "embree"
                                : o.renderer == 0 ? "preview"
                                : o.renderer == 2 ? gpuAcceleratorName(accelerator)
                                : accelerator < 0 ? o.accelerator
                                                  : acceleratorName(accelerator);
  const uint64_t pixels = uint64_t(o.width) * uint64_t(o.height);
  if (o.scene == "spheres")
    checkRunFitsInMemory(o.scene, o.renderer, structure, sphereFieldTriangles(o.triangles), pixels);
  const Scene scene = loadScene(o.scene, sceneOptions);
  checkRunFitsInMemory(o.scene, o.renderer, structure, scene.triangles.size(), pixels);
  if (scene.triangles.empty()) throw std::runtime_error(o.scene + ": the scene has no triangles");
  if (std::none_of(scene.triangles.begin(), scene.triangles.end(), hasArea) && !o.quiet)
    std::cerr << "passtrace: warning: " << o.scene << ": every triangle has zero area; only the background is visible\n";
  const std::vector<CameraSpec> views = cameraViews(scene, o);
  for (const CameraSpec& v : views) makeCameraBasis(v, o.width, o.height);  // reject a bad camera before building

  AccelBuildConfig build;
  build.kayKajiya.swapProbability = 0.5f * float(o.swapChildren);
  build.gsTries = o.gsTries;
  build.gridMultiplier = o.gridMultiplier;
  build.kdMinElements = o.kdMinElements;
  build.kdMaxDepth = o.kdMaxDepth;
  build.triangleTest = *triangleTestByName(o.triangleTest);  // the parser accepts only valid names

  std::unique_ptr<GpuTraversal> gpuTraversal;
  std::unique_ptr<GpuRenderer> gpuRenderer;
  std::unique_ptr<CpuAccelerator> cpuAccelerator;
  std::unique_ptr<CpuRenderer> cpuRenderer;
  AccelStats accelStats;
  RenderFn render;
  if (o.renderer == 2) {
    const GridKernels gridKernels = o.gridKernels == "split" ? GridKernels::Split : GridKernels::Merged;
    gpuTraversal = makeGpuTraversal(accelerator, scene, GpuTraversalConfig{build, o.loopLimit, gridKernels, o.pageTexels});
    gpuRenderer = std::make_unique<GpuRenderer>(scene, *gpuTraversal, o.width, o.height, o.pageTexels);
    accelStats = gpuTraversal->stats();
    render = [&](const CameraSpec& v, bool hits) { return gpuRenderer->render(v, o.bounces, hits); };
    // One untimed frame first: llvmpipe compiles each kernel on its first draw.
    render(views.front(), false);
  } else if (o.renderer == 1 || o.renderer == 3) {
    // Embree runs through the same CPU renderer: same rays, bounces and shading.
    cpuAccelerator = o.renderer == 3 ? makeEmbreeAccelerator(scene.triangles)
                                     : makeCpuAcceleratorFor(o.accelerator, scene, build);
    cpuRenderer = std::make_unique<CpuRenderer>(scene, *cpuAccelerator, o.threads);
    accelStats = cpuAccelerator->stats();
    render = [&](const CameraSpec& v, bool hits) { return cpuRenderer->render(v, o.width, o.height, o.bounces, hits); };
  } else {
    if (!o.hits.empty() || !o.heatmap.empty())
      throw std::runtime_error("--hits and --heatmap need a ray tracer (-r 1 or -r 2)");
    accelStats.name = "none";
    render = [&](const CameraSpec& v, bool) { return renderPreview(scene, v, o.width, o.height); };
  }

  // Per angle, the fastest of the repeats (thesis 10.1.1); the frame of angle
  // 0 is kept for the image and hit outputs.
  FrameResult first;
  std::vector<FrameResult> dumped;
  nlohmann::json frames = nlohmann::json::array();
  double sumMs = 0, sumRays = 0;
  FrameStats total;
  for (size_t k = 0; k < views.size(); ++k) {
    FrameResult best;
    for (int r = 0; r < o.repeats; ++r) {
      FrameResult frame = render(views[k], k == 0 && r == 0 && !o.hits.empty());
      if (r == 0 || frame.stats.frameMs < best.stats.frameMs) {
        if (k == 0 && r == 0) first.primaryHits = std::move(frame.primaryHits);
        best = std::move(frame);
      }
    }
    frames.push_back({{"angle", k}, {"frame_ms", best.stats.frameMs}, {"rays", best.stats.rays},
                      {"passes", best.stats.passes}});
    sumMs += best.stats.frameMs;
    sumRays += double(best.stats.rays);
    total.passes += best.stats.passes;
    total.steps += best.stats.steps;
    total.triangleTests += best.stats.triangleTests;
    if (k == 0) {
      first.width = best.width, first.height = best.height, first.rgb = best.rgb, first.stats = best.stats;
      first.steps = best.steps;
    }
    if (o.dumpImages && !o.output.empty()) writeImage(numberedPath(o.output, int(k)), best.width, best.height, best.rgb);
  }

  const double n = double(views.size());
  const double frameMs = sumMs / n;
  const double rays = sumRays / n;
  const double mraysPerS = frameMs > 0 ? rays / frameMs / 1000.0 : 0.0;
  if (!o.output.empty()) writeImage(o.output, first.width, first.height, first.rgb);
  if (!o.hits.empty()) {
    // Hit distances in the file's units: 2^-k undoes the rescaling exactly.
    for (HitRecord& h : first.primaryHits) h.t = std::ldexp(h.t, -scene.scaleExponent);
    writeHitBuffer(o.hits, first.width, first.height, first.primaryHits);
  }
  if (!o.heatmap.empty()) writeImage(o.heatmap, first.width, first.height, heatmapRgb(first.steps));
  if (!o.json.empty()) {
    nlohmann::json j = {
        {"scene", scene.name},
        {"triangles", scene.triangles.size()},
        {"renderer", kRendererNames[o.renderer]},
        {"renderer_id", o.renderer},
        {"accelerator", accelStats.name},
        {"accelerator_id", o.renderer == 0 || accelerator < 0 ? nlohmann::json(nullptr) : nlohmann::json(accelerator)},
        {"triangle_test", o.renderer == 0   ? nlohmann::json(nullptr)
                          : o.renderer == 3 ? nlohmann::json("embree")
                                            : nlohmann::json(o.triangleTest)},
        {"width", o.width},
        {"height", o.height},
        {"bounces", o.bounces},
        {"repeats", o.repeats},
        {"angles", views.size()},
        {"rays", rays},
        {"build_ms", accelStats.buildMs},
        {"frame_ms", frameMs},
        {"mrays_per_s", mraysPerS},
        {"passes", double(total.passes) / n},
        {"steps_per_ray", sumRays > 0 ? double(total.steps) / sumRays : 0.0},
        {"triangle_tests_per_ray", sumRays > 0 ? double(total.triangleTests) / sumRays : 0.0},
        {"accel_floats_per_triangle", accelStats.floatsPerTriangle},
        {"accel_nodes", accelStats.nodes},
        {"accel_leaves", accelStats.leaves},
        {"accel_depth", accelStats.depth},
        {"accel_references", accelStats.references},
        {"steps", double(total.steps) / n},
        {"triangle_tests", double(total.triangleTests) / n},
        {"gl_renderer", gl ? nlohmann::json(gl->renderer()) : nlohmann::json(nullptr)},
        {"gl_backend", gl ? nlohmann::json(gl->backend()) : nlohmann::json(nullptr)},
        {"frames", frames},
    };
    writeTextFile(o.json, j.dump(2) + "\n");
  }
  if (o.stats && !o.quiet) {
    std::printf("structure: %s, %zu nodes, %zu leaves, %zu triangle references, depth %u, %.2f floats/triangle\n",
                accelStats.name.c_str(), accelStats.nodes, accelStats.leaves, accelStats.references, accelStats.depth,
                accelStats.floatsPerTriangle);
    std::printf("per ray: %.2f traversal steps, %.2f triangle tests\n", sumRays > 0 ? double(total.steps) / sumRays : 0.0,
                sumRays > 0 ? double(total.triangleTests) / sumRays : 0.0);
  }
  if (!o.quiet) {
    std::printf("%s: %zu triangles; %s renderer, %s (build %.1f ms, %.2f floats/triangle)%s%s\n", scene.name.c_str(),
                scene.triangles.size(), kRendererNames[o.renderer], accelStats.name.c_str(), accelStats.buildMs,
                accelStats.floatsPerTriangle, gl ? " on " : "", gl ? gl->renderer().c_str() : "");
    std::printf("%dx%d, %d bounces, %zu view(s): %.0f rays in %.2f ms per frame = %.3f Mrays/s (%.0f passes)\n",
                o.width, o.height, o.bounces, views.size(), rays, frameMs, mraysPerS, double(total.passes) / n);
  }
}

}  // namespace passtrace
