#include "render/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "accel/milliseconds_since.h"
#include "passtrace_version.h"
#include "render/camera.h"
#include "render/camera_path.h"
#include "render/cone_session.h"
#include "render/dynamic_renderer.h"
#include "render/gpu_renderer.h"
#include "render/heatmap.h"
#include "render/image_output.h"
#include "render/memory_check.h"
#include "render/output_files.h"
#include "render/rank_exchange.h"
#include "render/ranks.h"
#include "render/renderer.h"
#include "scenes/scene_export.h"
#include "scenes/scene_lights.h"
#include "scenes/scene_scale.h"
#include "stream/inout_stream.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

// Batch tracers' counters summed over n frames, per frame.
std::optional<FilterStats> meanFilter(const std::optional<FilterStats>& sum, uint64_t n) {
  if (!sum || n == 0) return sum;
  FilterStats mean = *sum;
  for (uint64_t* c : {&mean.rayBox, &mean.coneBox, &mean.triangleBox, &mean.rayTriangle, &mean.nodes}) *c /= n;
  return mean;
}

std::vector<CameraSpec> cameraViews(const Scene& scene, const RunSettings& o) {
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

// One frame traced by every MPI rank, each its own rows (RendererConfig::rows).
// Rank 0 gets the whole frame; the others get their band. Its frame time is
// the slowest rank's, timed as one process times a frame (allocation and
// read-back excluded), plus rank 0 packing its band and gathering and placing
// every rank's rows. `traceMs` adds this rank's own render time.
FrameResult renderBands(Renderer& renderer, const CameraSpec& view, bool captureHits, int fullHeight, double& traceMs) {
  ranks::agree();  // the ranks start together
  FrameResult band = renderer.render(view, captureHits);
  traceMs += band.stats.frameMs;
  const auto packStart = std::chrono::steady_clock::now();
  const std::string packed = packBand(band);
  const double packMs = millisecondsSince(packStart);
  ranks::agree();  // every band is ready: the exchange starts
  const auto exchangeStart = std::chrono::steady_clock::now();
  const std::vector<std::string> parts = ranks::gatherOnRoot(packed);
  if (!ranks::isRoot()) return band;
  FrameResult whole = assembleBands(parts, fullHeight);
  whole.stats.frameMs += packMs + millisecondsSince(exchangeStart);
  return whole;
}

// What the chosen renderer keeps per pixel beyond the memory check's base.
double extraBytesPerPixel(const RunSettings& o) {
  return o.renderer == RendererId::Gpu ? GpuRenderer::extraBytesPerPixel(o.shading, o.gpu.compact, o.gpu.stage) : 0.0;
}

void checkOutputs(const RunSettings& o) {
  if (!o.output.empty()) {
    checkWritable(o.output);
    checkImageFormat(o.output);
  }
  if (!o.hits.empty()) {
    checkWritable(o.hits);
    if (fs::path(o.hits).extension() != ".exr") throw std::runtime_error(o.hits + ": hit buffers are OpenEXR (.exr) files");
    checkImageFormat(o.hits);
  }
  if (!o.json.empty()) checkWritable(o.json);
  if (!o.heatmap.empty()) {
    checkWritable(o.heatmap);
    checkImageFormat(o.heatmap);
  }
}

// In double: the cross product of tiny edges underflows in float.
bool hasArea(const Triangle& t) {
  const glm::dvec3 v0(t.v0);
  const glm::dvec3 n = glm::cross(glm::dvec3(t.v1) - v0, glm::dvec3(t.v2) - v0);
  return n != glm::dvec3(0.0);
}

// The structure -a names on this renderer (null for the preview), and a
// warning for each given flag it does not read.
const Structure* chooseStructure(const RunSettings& o, RunReport& report, Progress& progress) {
  auto warn = [&](const std::string& message) {
    report.warnings.push_back(message);
    progress.warn(message);
  };
  const Structure* structure = nullptr;
  if (o.renderer == RendererId::Embree) {
    structure = findStructure("embree");
    if (!structure) throw std::runtime_error("this passtrace was built without Embree (-r 3 is not available)");
    if (o.structureGiven && o.structure != "embree") warn("-a/--accel is not read by the Embree renderer (ignored)");
  } else if (o.renderer == RendererId::OpenGl) {
    if (o.structureGiven) warn("-a/--accel is not read by the OpenGL preview (ignored)");
  } else {
    structure = &resolveStructure(o.structure, o.renderer);
  }
  std::vector<BuildParam> unused = o.givenParams;
  if (structure) unused = unusedParams(*structure, o.renderer, o.givenParams);
  for (BuildParam p : unused)
    warn(std::string(buildParamFlag(p)) + " is not read by " +
         (structure ? std::string(structure->name) + " on the " : std::string("the ")) +
         std::string(rendererTitle(o.renderer)) + " renderer (ignored)");
  return structure;
}


// --export: the scene as loaded, written instead of rendered.
RunReport exportOnly(const RunSettings& o, Progress& progress) {
  if (!isExportFormat(o.exportPath))
    throw std::runtime_error("--export " + o.exportPath + ": unknown format (expected .obj, .gltf or .glb)");
  if (!o.output.empty() || !o.hits.empty() || !o.heatmap.empty() || !o.json.empty())
    throw std::runtime_error("--export writes the scene and renders nothing: -o, --hits, --heatmap and --json do not apply");
  checkWritable(o.exportPath);
  RunReport report;
  report.version = kVersion;
  progress.stage("loading " + o.scene);
  const Scene scene = loadScene(o.scene, o.sceneOptions);
  progress.stage("writing " + o.exportPath);
  OutputFiles outputs;
  for (const ExportedFile& file : exportFiles(scene, o.exportPath)) outputs.write(file.path, file.bytes);
  outputs.commitAll();
  progress.finish();
  report.scene = scene.name;
  report.triangles = scene.triangles.size();
  report.exported = o.exportPath;
  return report;
}

// What every rendering run does before loading: the structure (an unknown
// one is rejected before anything is read), the image size and the outputs
// checked, and the GL context, whose limits on the image size are known
// before anything is built.
struct Prepared {
  const Structure* structure = nullptr;
  bool cpuTraced = false;
  std::unique_ptr<GlContext> gl;
};

Prepared prepare(const RunSettings& o, RunReport& report, Progress& progress) {
  report.version = kVersion;
  Prepared p;
  p.structure = chooseStructure(o, report, progress);
  p.cpuTraced = o.renderer == RendererId::Cpu || o.renderer == RendererId::Embree;
  if (p.cpuTraced && (long long)o.width * o.height > 16384LL * 16384LL)
    throw std::runtime_error("image " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " is too large for the CPU renderer (at most 16384x16384 pixels)");
  if (o.renderer == RendererId::OpenGl && (!o.hits.empty() || !o.heatmap.empty()))
    throw std::runtime_error("--hits and --heatmap need a ray tracer (-r 1 or -r 2)");
  checkOutputs(o);
  if (!p.cpuTraced) {
    std::string notices;
    p.gl = GlContext::create(o.glBackend, &notices);
    if (!notices.empty()) progress.notice(notices);
    InOutStream::checkSize(o.width, o.height);
    report.glRenderer = p.gl->renderer();
    report.glBackend = p.gl->backend();
  }
  return p;
}

// The report's fields that name the run rather than measure it.
void describeRun(const RunSettings& o, const Structure* structure, RunReport& report) {
  report.renderer = std::string(rendererName(o.renderer));
  report.rendererId = int(o.renderer);
  if (structure && structure->number && structure->numberedOn.has(o.renderer)) report.structureNumber = structure->number;
  if (o.renderer == RendererId::Embree) report.triangleTest = "embree";
  else if (o.renderer != RendererId::OpenGl) report.triangleTest = triangleTestName(o.gpu.build.triangleTest);
  report.width = o.width, report.height = o.height, report.bounces = o.bounces, report.repeats = o.repeats;
  report.shading = shadingModeName(o.shading.mode);
  report.compact = o.renderer == RendererId::Gpu ? compactionName(o.gpu.compact) : "off";
  if (o.renderer == RendererId::Gpu) report.stage = streamStageName(o.gpu.stage);
  report.stepsVisitNodes = structure && o.renderer == RendererId::Cpu && structure->cpuStepsVisitNodes;
}

// "out.png", k -> "out_0007.png": a sequence's frames sort by name.
fs::path sequencePath(const fs::path& path, int k) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", k);
  return path.parent_path() / (path.stem().string() + number + path.extension().string());
}

// --dynamic: only with a structure that reads it, on the CPU or GPU stream
// renderer (an error, not the unused-flag warning: the run would not measure
// what was asked).
void checkDynamic(const RunSettings& o) {
  if (std::find(o.givenParams.begin(), o.givenParams.end(), BuildParam::Dynamic) == o.givenParams.end()) return;
  if (o.renderer != RendererId::Cpu && o.renderer != RendererId::Gpu)
    throw std::runtime_error("--dynamic needs the CPU or the GPU stream renderer (-r 1 or -r 2)");
  const Structure& s = resolveStructure(o.structure, o.renderer);
  const std::vector<BuildParam> reads = s.readsOn(o.renderer);
  if (std::find(reads.begin(), reads.end(), BuildParam::Dynamic) == reads.end()) {
    std::string valid;
    for (const Structure& row : structures()) {
      const std::vector<BuildParam> r = row.readsOn(o.renderer);
      if (std::find(r.begin(), r.end(), BuildParam::Dynamic) != r.end())
        valid += (valid.empty() ? "" : ", ") + std::string(row.name);
    }
    throw std::runtime_error("--dynamic: " + std::string(s.name) + " has no dynamic strategies on the " +
                             std::string(rendererTitle(o.renderer)) + " renderer (valid: " + valid + ")");
  }
}

// --frames N: the scene at N times over [start, end] (default: its animation
// range), one image (and hit buffer) per frame. The structure is rebuilt
// each frame, or with --dynamic two-trees/merge only its dynamic part
// (render/dynamic_renderer.h); the JSON's "sequence" has each frame's build
// (or build and merge) and trace times and their sum T_F.
RunReport renderSequence(const RunSettings& o, Progress& progress) {
  if (!o.heatmap.empty() || o.angles != 1 || o.dumpImages)
    throw std::runtime_error("--frames renders one image per frame: --heatmap, -n and -p do not apply");
  checkDynamic(o);
  RunReport report;
  const Prepared p = prepare(o, report, progress);
  SceneOptions sceneOptions = o.sceneOptions;
  progress.stage("loading " + o.scene);
  Scene scene = loadScene(o.scene, sceneOptions);
  if (!scene.animation && !(o.timeStart && o.timeEnd))
    throw std::runtime_error(o.scene + ": the scene has no animation: give --time-start and --time-end for --frames");
  const float start = o.timeStart ? *o.timeStart : scene.animation->start;
  const float end = o.timeEnd ? *o.timeEnd : scene.animation->end;
  if (!(start <= end)) throw std::runtime_error("--frames: the start time " + std::to_string(start) +
                                                " is after the end time " + std::to_string(end));
  const fs::path pattern = o.output.empty() ? fs::path("frame.png") : fs::path(o.output);
  if (o.output.empty()) checkImageFormat(pattern.string());
  const bool keepsStatic = o.dynamic != DynamicStrategy::Rebuild;
  const int firstScaleExponent = scene.scaleExponent;
  RendererConfig config{o.width, o.height, o.bounces, o.threads, o.gpu, o.shading, {}};
  std::unique_ptr<DynamicRenderer> dynamic;  // two-trees, merge: kept across frames
  // Under mpirun the frames are dealt out in turn among the ranks (each
  // frame's structure is built for it alone; two-trees and merge rebuild the
  // dynamic part from the static tree every frame, so no frame depends on
  // the one before); rank 0 gathers them.
  const int rankCount = ranks::count(), rank = ranks::index();
  RankShare share;
  share.run = RankRun{rank, ranks::host(), 0, 0, 0};
  for (int f = rank; f < o.frames; f += rankCount) {
    const float time = o.frames == 1 ? start : start + (end - start) * float(f) / float(o.frames - 1);
    if (f > 0 || time != sceneOptions.time) {
      sceneOptions.time = time;
      scene = loadScene(o.scene, sceneOptions);  // in place: the dynamic renderer holds a reference
    }
    checkRunFitsInMemory(o.scene, o.renderer, p.structure, scene.triangles.size(), uint64_t(o.width) * uint64_t(o.height),
                         extraBytesPerPixel(o));
    if (scene.triangles.empty()) throw std::runtime_error(o.scene + ": the scene has no triangles");
    // The static tree is built in the first frame's coordinates.
    if (keepsStatic && scene.scaleExponent != firstScaleExponent)
      throw std::runtime_error(o.scene + ": the scene's rescaling changes over the frames; use --dynamic rebuild");
    const CameraSpec view = cameraViews(scene, o).front();
    makeCameraBasis(view, o.width, o.height);
    placeLights(scene, o.lights, view);
    progress.frame(size_t(f), size_t(o.frames));
    std::unique_ptr<Renderer> rebuilt;
    Renderer* renderer = nullptr;
    double buildMs = 0;
    const bool firstOfRank = f == rank;
    if (keepsStatic) {
      if (!dynamic) {
        dynamic = makeDynamicRenderer(o.dynamic, o.renderer, *p.structure, scene, config);
        report.staticBuildMs = dynamic->staticBuildMs();
        share.run.buildMs += report.staticBuildMs;
      }
      buildMs = dynamic->nextFrame();
      renderer = dynamic.get();
      if (o.renderer == RendererId::Gpu && firstOfRank) renderer->render(view, false);  // llvmpipe compiles on the first draw
    } else {
      rebuilt = makeRenderer(o.renderer, p.structure, scene, config);
      renderer = rebuilt.get();
      buildMs = renderer->structureStats().buildMs;
      if (o.renderer == RendererId::Gpu) renderer->render(view, false);  // llvmpipe compiles on the first draw
    }
    FrameResult best;
    std::vector<HitRecord> hits;
    for (int r = 0; r < o.repeats; ++r) {
      FrameResult frame = renderer->render(view, r == 0 && !o.hits.empty());
      share.run.traceMs += frame.stats.frameMs;
      if (r == 0) hits = std::move(frame.primaryHits);
      if (r == 0 || frame.stats.frameMs < best.stats.frameMs) best = std::move(frame);
    }
    const fs::path image = sequencePath(pattern, f);
    share.files.push_back({image.string(), encodeImage(image, best.width, best.height, best.rgb)});
    if (f == 0) report.image = best.rgb;
    if (!o.hits.empty()) {
      // Hit distances in the file's units: 2^-k undoes the rescaling exactly.
      for (HitRecord& h : hits) h.t = std::ldexp(h.t, -scene.scaleExponent);
      const fs::path hitFile = sequencePath(o.hits, f);
      share.files.push_back({hitFile.string(), encodeHitBuffer(hitFile, best.width, best.height, hits)});
    }
    const AccelStats stats = renderer->structureStats();
    if (!keepsStatic) share.run.buildMs += buildMs;
    ++share.run.share;
    SequenceFrame record;
    record.frame = size_t(f), record.time = time, record.triangles = scene.triangles.size();
    record.movingTriangles = size_t(std::count(scene.moving.begin(), scene.moving.end(), uint8_t(1)));
    record.buildMs = buildMs, record.frameMs = best.stats.frameMs, record.rays = double(best.stats.rays);
    record.totalMs = record.buildMs + record.frameMs;
    record.mraysPerS = record.frameMs > 0 ? record.rays / record.frameMs / 1000.0 : 0.0;
    share.frames.push_back({record, best.stats, stats});
  }
  progress.finish();

  // Every rank's frames to rank 0, merged in frame order: the sums are a single process's.
  std::vector<SequenceOutcome> frames;
  OutputFiles outputs;  // every frame's files appear together, after the last frame
  const std::vector<std::string> parts = ranks::gatherOnRoot(packShare(share));
  if (!ranks::isRoot()) return report;
  for (const std::string& bytes : parts) {
    RankShare s = unpackShare(bytes);
    frames.insert(frames.end(), s.frames.begin(), s.frames.end());
    for (FileBytes& file : s.files) outputs.write(file.path, file.bytes);
    report.rankRuns.push_back(s.run);
  }
  std::sort(frames.begin(), frames.end(),
            [](const SequenceOutcome& a, const SequenceOutcome& b) { return a.record.frame < b.record.frame; });
  double sumMs = 0, sumRays = 0, sumSteps = 0, sumTests = 0, sumPasses = 0;
  std::optional<FilterStats> sumFilter;
  for (const SequenceOutcome& frame : frames) {
    const FrameStats& best = frame.stats;
    report.sequence.push_back(frame.record);
    report.structure = frame.structure;
    sumMs += best.frameMs, sumRays += double(best.rays), sumPasses += double(best.passes);
    sumSteps += double(best.steps), sumTests += double(best.triangleTests);
    report.maxStepsPerRay = std::max(report.maxStepsPerRay, best.maxStepsPerRay);
    report.maxTriangleTestsPerRay = std::max(report.maxTriangleTestsPerRay, best.maxTriangleTestsPerRay);
    if (best.filter) sumFilter = sumFilter.value_or(FilterStats{}) += *best.filter;
  }
  const double n = double(o.frames);
  report.ranks = rankCount;
  report.dynamic = std::string(dynamicStrategyName(o.dynamic));
  report.scene = scene.name;
  report.triangles = frames.back().record.triangles;  // the last frame's, as one process reports it
  describeRun(o, p.structure, report);
  report.angles = 1;
  report.rays = sumRays / n, report.frameMs = sumMs / n, report.passes = sumPasses / n;
  report.mraysPerS = report.frameMs > 0 ? report.rays / report.frameMs / 1000.0 : 0.0;
  report.steps = sumSteps / n, report.triangleTests = sumTests / n;
  report.stepsPerRay = sumRays > 0 ? sumSteps / sumRays : 0.0;
  report.triangleTestsPerRay = sumRays > 0 ? sumTests / sumRays : 0.0;
  report.dacrt = meanFilter(sumFilter, uint64_t(o.frames));
  if (!o.json.empty()) outputs.write(o.json, toJson(report).dump(2) + "\n");
  outputs.commitAll();
  return report;
}

}  // namespace

RunReport runSession(const RunSettings& o, Progress& progress) {
  if (o.gpu.stage != StreamStage::Fragment && o.renderer != RendererId::Gpu)
    throw std::runtime_error("--stage compute needs the GPU stream renderer (-r 2)");
  // Every stream and kernel of the run (structure, renderer, compaction,
  // cones, a sequence's rebuilt kernels) is made in the run's stage.
  const StreamStageScope stage(o.renderer == RendererId::Gpu ? o.gpu.stage : StreamStage::Fragment);
  if (o.cone) checkConeRun(o);  // before anything is loaded
  if (!o.exportPath.empty()) return ranks::isRoot() ? exportOnly(o, progress) : RunReport{};
  if (o.frames > 0) return renderSequence(o, progress);
  RunReport report;
  Prepared prepared = prepare(o, report, progress);
  const Structure* structure = prepared.structure;
  // Say so before trying: the procedural scene's size is known before it is
  // made, a file's once it is read.
  // Under mpirun one frame is divided among the ranks by rows; not the
  // preview's rasterizer, which has no rows to divide, nor a batch tracer,
  // whose counts depend on the rays traced together: rank 0 renders those.
  const bool banded = ranks::count() > 1 && o.angles == 1 && o.renderer != RendererId::OpenGl &&
                      !(o.renderer == RendererId::Cpu && structure->cpuRayGrouping == RayGrouping::Generation);
  if (banded && o.height < ranks::count())
    throw std::runtime_error("--height " + std::to_string(o.height) + ": fewer rows than the " +
                             std::to_string(ranks::count()) + " MPI ranks to divide them among");
  // This rank's rows (the renderer's config below takes the same bands).
  const RowBands bands = banded ? RowBands::interleaved(o.height, ranks::count(), ranks::index()) : RowBands{};
  const uint64_t pixels = uint64_t(o.width) * uint64_t(banded ? bands.localHeight() : o.height);
  if (o.scene == "spheres")
    checkRunFitsInMemory(o.scene, o.renderer, structure, sphereFieldTriangles(o.sceneOptions.triangles), pixels,
                         extraBytesPerPixel(o));
  progress.stage("loading " + o.scene);
  Scene scene = loadScene(o.scene, o.sceneOptions);
  checkRunFitsInMemory(o.scene, o.renderer, structure, scene.triangles.size(), pixels, extraBytesPerPixel(o));
  if (scene.triangles.empty()) throw std::runtime_error(o.scene + ": the scene has no triangles");
  if (std::none_of(scene.triangles.begin(), scene.triangles.end(), hasArea)) {
    report.warnings.push_back(o.scene + ": every triangle has zero area; only the background is visible");
    progress.warn(report.warnings.back());
  }
  const std::vector<CameraSpec> views = cameraViews(scene, o);
  for (const CameraSpec& v : views) makeCameraBasis(v, o.width, o.height);  // reject a bad camera before building
  placeLights(scene, o.lights, views.front());
  OutputFiles outputs;  // every file of the run appears together, at the end
  if (o.cone) {
    if (!ranks::isRoot()) return report;  // not divided: rank 0 traces the cones
    traceConeRun(o, *structure, scene, views, report, progress, outputs);
    report.scene = scene.name;
    report.triangles = scene.triangles.size();
    describeRun(o, structure, report);
    report.angles = views.size();
    if (!o.json.empty()) outputs.write(o.json, toJson(report).dump(2) + "\n");
    outputs.commitAll();
    return report;
  }

  // Under mpirun (render/ranks.h): one frame's rows, or the angles, divided
  // among the ranks; rank 0 gathers them and writes everything.
  const int rankCount = ranks::count(), rank = ranks::index();
  RendererConfig config{o.width, o.height, o.bounces, o.threads, o.gpu, o.shading, {}};
  if (banded) config.rows = bands, config.height = bands.localHeight();
  std::vector<size_t> mine;  // the angles this rank renders
  for (size_t k = 0; k < views.size(); ++k)
    if (banded || int(k % size_t(rankCount)) == rank) mine.push_back(k);

  RankShare share;
  share.run = RankRun{rank, ranks::host(), 0, 0, banded ? size_t(config.height) : mine.size()};
  std::unique_ptr<Renderer> renderer;
  if (!mine.empty()) {
    if (structure)
      progress.stage("building " + std::string(structure->name) + " over " + std::to_string(scene.triangles.size()) +
                     " triangles" + (o.renderer == RendererId::Gpu ? " and uploading it" : ""));
    renderer = makeRenderer(o.renderer, structure, scene, config);
    share.run.buildMs = renderer->structureStats().buildMs;
    if (o.renderer == RendererId::Gpu) {
      // One untimed frame first: llvmpipe compiles each kernel on its first draw.
      progress.stage("compiling the kernels");
      renderer->render(views[mine.front()], false);
    }
  }

  // Per angle, the fastest of the repeats; the frame of angle 0 (rank 0's) is
  // kept for the image and hit outputs.
  FrameResult first;
  for (size_t k : mine) {
    FrameResult best;
    for (int r = 0; r < o.repeats; ++r) {
      progress.frame(k * size_t(o.repeats) + size_t(r), views.size() * size_t(o.repeats));
      const bool capture = k == 0 && r == 0 && !o.hits.empty();
      FrameResult frame = banded ? renderBands(*renderer, views[k], capture, o.height, share.run.traceMs)
                                 : renderer->render(views[k], capture);
      if (!banded) share.run.traceMs += frame.stats.frameMs;
      if (r == 0 || frame.stats.frameMs < best.stats.frameMs) {
        if (k == 0 && r == 0) first.primaryHits = std::move(frame.primaryHits);
        best = std::move(frame);
      }
    }
    share.angles.push_back({k, best.stats});
    if (k == 0) {
      first.width = best.width, first.height = best.height, first.rgb = best.rgb, first.stats = best.stats;
      first.steps = best.steps;
    }
    if (o.dumpImages && !o.output.empty()) {
      const fs::path dump = numberedPath(o.output, int(k));
      share.files.push_back({dump.string(), encodeImage(dump, best.width, best.height, best.rgb)});
    }
    if (banded && !ranks::isRoot()) share.angles.clear(), share.files.clear();  // rank 0 has the whole frame
  }
  progress.finish();
  report.structure = renderer ? renderer->structureStats() : AccelStats{.name = "none"};

  // Every rank's share to rank 0, merged in angle order: the sums are a single process's.
  std::vector<RankShare> shares;
  for (const std::string& bytes : ranks::gatherOnRoot(packShare(share))) shares.push_back(unpackShare(bytes));
  if (!ranks::isRoot()) return report;
  std::vector<AngleOutcome> angles;
  for (RankShare& s : shares) {
    angles.insert(angles.end(), s.angles.begin(), s.angles.end());
    for (FileBytes& f : s.files) outputs.write(f.path, f.bytes);
    report.rankRuns.push_back(s.run);
  }
  std::sort(angles.begin(), angles.end(), [](const AngleOutcome& a, const AngleOutcome& b) { return a.angle < b.angle; });
  double sumMs = 0, sumRays = 0;
  FrameStats total;
  for (const AngleOutcome& a : angles) {
    const FrameStats& best = a.stats;
    report.frames.push_back({a.angle, best.frameMs, best.rays, best.passes});
    sumMs += best.frameMs;
    sumRays += double(best.rays);
    total.passes += best.passes;
    total.steps += best.steps;
    total.triangleTests += best.triangleTests;
    total.maxStepsPerRay = std::max(total.maxStepsPerRay, best.maxStepsPerRay);
    total.maxTriangleTestsPerRay = std::max(total.maxTriangleTestsPerRay, best.maxTriangleTestsPerRay);
    if (best.filter) total.filter = total.filter.value_or(FilterStats{}) += *best.filter;
  }

  const double n = double(views.size());
  report.scene = scene.name;
  report.triangles = scene.triangles.size();
  describeRun(o, structure, report);
  report.ranks = rankCount;
  report.angles = views.size();
  report.rays = sumRays / n;
  report.frameMs = sumMs / n;
  report.mraysPerS = report.frameMs > 0 ? report.rays / report.frameMs / 1000.0 : 0.0;
  report.passes = double(total.passes) / n;
  report.steps = double(total.steps) / n;
  report.triangleTests = double(total.triangleTests) / n;
  report.stepsPerRay = sumRays > 0 ? double(total.steps) / sumRays : 0.0;
  report.triangleTestsPerRay = sumRays > 0 ? double(total.triangleTests) / sumRays : 0.0;
  report.maxStepsPerRay = total.maxStepsPerRay;
  report.maxTriangleTestsPerRay = total.maxTriangleTestsPerRay;
  report.dacrt = meanFilter(total.filter, uint64_t(views.size()));

  if (!o.output.empty()) outputs.write(o.output, encodeImage(o.output, first.width, first.height, first.rgb));
  if (!o.hits.empty()) {
    // Hit distances in the file's units: 2^-k undoes the rescaling exactly.
    for (HitRecord& h : first.primaryHits) h.t = std::ldexp(h.t, -scene.scaleExponent);
    outputs.write(o.hits, encodeHitBuffer(o.hits, first.width, first.height, first.primaryHits));
  }
  if (!o.heatmap.empty())
    outputs.write(o.heatmap, encodeImage(o.heatmap, first.width, first.height, heatmapRgb(first.steps)));
  if (!o.json.empty()) outputs.write(o.json, toJson(report).dump(2) + "\n");
  outputs.commitAll();
  report.image = std::move(first.rgb);
  return report;
}

}  // namespace passtrace
