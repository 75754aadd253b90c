#include "render/cone_session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "render/cone_tracer.h"
#include "render/gpu_cone_tracer.h"
#include "render/heatmap.h"
#include "render/image_output.h"

namespace passtrace {
namespace {

// The structures with a cone query on the renderer (-r 1: Structure::cone,
// -r 2: Structure::coneStream).
bool hasCone(const Structure& s, RendererId renderer) {
  return renderer == RendererId::Gpu ? s.coneStream != nullptr : s.cone != nullptr;
}

std::string coneStructureNames(RendererId renderer) {
  std::string names;
  for (const Structure& s : structures())
    if (hasCone(s, renderer) && s.runsOn(renderer)) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

}  // namespace

void checkConeRun(const RunSettings& o) {
  if (o.renderer != RendererId::Cpu && o.renderer != RendererId::Gpu)
    throw std::runtime_error("--cone: cone queries run on the CPU renderer (-r 1), with " +
                             coneStructureNames(RendererId::Cpu) + ", and the stream path (-r 2), with " +
                             coneStructureNames(RendererId::Gpu));
  const Structure& s = resolveStructure(o.structure, o.renderer);
  if (!hasCone(s, o.renderer))
    throw std::runtime_error("--cone: " + std::string(s.name) + " has no cone traversal on the " +
                             std::string(rendererTitle(o.renderer)) + " renderer (structures with one: " +
                             coneStructureNames(o.renderer) + ")");
  if (o.frames > 0 || !o.exportPath.empty())
    throw std::runtime_error("--cone traces one frame: --frames and --export do not apply");
  if (!o.output.empty() || !o.hits.empty() || o.dumpImages)
    throw std::runtime_error("--cone writes --cone-hits, --heatmap and --json: -o, --hits and -p do not apply");
  if (!o.coneHits.empty()) {
    checkWritable(o.coneHits);
    if (std::filesystem::path(o.coneHits).extension() != ".exr")
      throw std::runtime_error("--cone-hits " + o.coneHits + ": cone hit buffers are OpenEXR (.exr) files");
  }
}

void traceConeRun(const RunSettings& o, const Structure& structure, const Scene& scene,
                  const std::vector<CameraSpec>& views, RunReport& report, Progress& progress, OutputFiles& outputs) {
  progress.stage("building " + std::string(structure.name) + " for cones over " +
                 std::to_string(scene.triangles.size()) + " triangles");
  const bool stream = o.renderer == RendererId::Gpu;
  std::unique_ptr<ConeTraversal> traversal;
  ConeStreamTree tree;
  if (stream) {
    tree = structure.coneStream(scene.triangles, o.gpu.build);
  } else {
    traversal = structure.cone(scene.triangles, o.gpu.build);
  }
  const float halfAngle = float(double(*o.cone) * std::numbers::pi / 180.0);
  ConeQueryConfig config{o.coneMax};
  config.sortedNodes = o.coneSortedNodes;
  if (config.sortedNodes && (structure.family != "bvh" || stream)) {
    report.warnings.push_back("--cone-nodes is not read by " + std::string(structure.name) +
                              (stream ? " on the stream path (stack traversal; ignored)" : " (ignored)"));
    progress.warn(report.warnings.back());
  }
  ConeFrame first;
  double sumMs = 0;
  ConeReport cone;
  cone.degrees = *o.cone, cone.maxHits = o.coneMax;
  double nodes = 0, triangles = 0, met = 0;
  for (size_t k = 0; k < views.size(); ++k) {
    const CameraBasis camera = makeCameraBasis(views[k], o.width, o.height);
    ConeFrame best;
    for (int r = 0; r < o.repeats; ++r) {
      progress.frame(k * size_t(o.repeats) + size_t(r), views.size() * size_t(o.repeats));
      ConeFrame frame = stream ? traceConesGpu(tree, camera, halfAngle, config,
                                               GpuConeConfig{o.gpu.loopLimit, o.coneCapacity})
                               : traceCones(*traversal, camera, halfAngle, config, o.threads);
      if (r == 0 || frame.ms < best.ms) best = std::move(frame);
    }
    report.frames.push_back({k, best.ms, uint64_t(best.hits.size()), 0});
    sumMs += best.ms;
    for (size_t i = 0; i < best.hits.size(); ++i) {
      nodes += best.nodes[i], triangles += best.triangles[i], met += best.hits[i].count;
      cone.nodesMax = std::max<uint64_t>(cone.nodesMax, best.nodes[i]);
      cone.trianglesMax = std::max<uint64_t>(cone.trianglesMax, best.triangles[i]);
      cone.metMax = std::max<uint64_t>(cone.metMax, best.hits[i].count);
    }
    if (k == 0) first = std::move(best);
  }
  progress.finish();
  const double cones = double(views.size()) * double(o.width) * double(o.height);
  cone.nodesMean = nodes / cones, cone.trianglesMean = triangles / cones, cone.metMean = met / cones;
  report.cone = cone;
  report.structure = stream ? tree.stats : traversal->stats();
  const double n = double(views.size());
  report.rays = cones / n;  // cones per frame
  report.frameMs = sumMs / n;
  report.mraysPerS = report.frameMs > 0 ? report.rays / report.frameMs / 1000.0 : 0.0;
  report.steps = nodes / n, report.triangleTests = triangles / n;
  report.stepsPerRay = nodes / cones, report.triangleTestsPerRay = triangles / cones;
  report.maxStepsPerRay = cone.nodesMax, report.maxTriangleTestsPerRay = cone.trianglesMax;
  if (!o.coneHits.empty()) {
    // Axis distances in the file's units: 2^-k undoes the rescaling exactly.
    for (ConeHitRecord& h : first.hits) h.t = std::ldexp(h.t, -scene.scaleExponent);
    outputs.write(o.coneHits, encodeConeHitBuffer(o.coneHits, first.width, first.height, first.hits));
  }
  if (!o.heatmap.empty()) {
    std::vector<float> cost(first.nodes.size());
    for (size_t i = 0; i < cost.size(); ++i) cost[i] = float(first.nodes[i]) + float(first.triangles[i]);
    outputs.write(o.heatmap, encodeImage(o.heatmap, first.width, first.height, heatmapRgb(cost)));
  }
}

}  // namespace passtrace
