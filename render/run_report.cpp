#include "render/run_report.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "accel/registry.h"

namespace passtrace {
namespace {

template <typename T>
nlohmann::json orNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::string format(const char* fmt, auto... args) {
  const int n = std::snprintf(nullptr, 0, fmt, args...);
  std::string text(size_t(n) + 1, '\0');
  std::snprintf(text.data(), text.size(), fmt, args...);
  text.pop_back();
  return text;
}

}  // namespace

std::optional<double> nodeTestsPerRay(const RunReport& r) {
  if (r.rendererId != int(RendererId::Cpu) && r.rendererId != int(RendererId::Gpu)) return std::nullopt;
  if (r.stepsVisitNodes) return r.stepsPerRay;
  return std::max(0.0, r.stepsPerRay - r.triangleTestsPerRay);
}

nlohmann::json toJson(const AccelStats& s) {
  return {{"accelerator", s.name},
          {"build_ms", s.buildMs},
          {"accel_floats_per_triangle", s.floatsPerTriangle},
          {"accel_nodes", s.nodes},
          {"accel_leaves", s.leaves},
          {"accel_depth", s.depth},
          {"accel_references", s.references},
          // The structure's cost and memory (0: not computed for this structure).
          {"structure",
           {{"sah_cost", s.sahCost},
            {"structure_bytes", s.structureBytes},
            {"node_test_bytes", s.nodeTestBytes},
            {"triangle_test_bytes", s.triangleTestBytes}}}};
}

nlohmann::json toJson(const RunReport& r) {
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameReport& f : r.frames)
    frames.push_back({{"angle", f.angle}, {"frame_ms", f.frameMs}, {"rays", f.rays}, {"passes", f.passes}});
  nlohmann::json j = {
      {"schema_version", kRunReportSchemaVersion},
      {"version", r.version},
      {"scene", r.scene},
      {"triangles", r.triangles},
      {"renderer", r.renderer},
      {"renderer_id", r.rendererId},
      {"accelerator_id", orNull(r.structureNumber)},
      {"triangle_test", orNull(r.triangleTest)},
      {"width", r.width},
      {"height", r.height},
      {"bounces", r.bounces},
      {"repeats", r.repeats},
      {"angles", r.angles},
      {"rays", r.rays},
      {"frame_ms", r.frameMs},
      {"mrays_per_s", r.mraysPerS},
      {"passes", r.passes},
      {"steps_per_ray", r.stepsPerRay},
      {"triangle_tests_per_ray", r.triangleTestsPerRay},
      {"max_steps_per_ray", r.maxStepsPerRay},
      {"max_triangle_tests_per_ray", r.maxTriangleTestsPerRay},
      {"steps", r.steps},
      {"triangle_tests", r.triangleTests},
      {"gl_renderer", orNull(r.glRenderer)},
      {"gl_backend", orNull(r.glBackend)},
      {"frames", frames},
      {"warnings", r.warnings},
  };
  j["shading"] = r.shading;
  j["compact"] = r.compact;
  j["stage"] = orNull(r.stage);
  // The processes the run was divided among (one without mpirun), each with its host and times.
  j["ranks"] = r.ranks;
  nlohmann::json rankRuns = nlohmann::json::array();
  for (const RankRun& k : r.rankRuns)
    rankRuns.push_back({{"rank", k.rank}, {"host", k.host}, {"build_ms", k.buildMs}, {"trace_ms", k.traceMs},
                        {"share", k.share}});
  j["rank_runs"] = rankRuns;
  // Only in --frames runs, so that a single frame's keys stay as they were.
  if (!r.sequence.empty()) {
    nlohmann::json sequence = nlohmann::json::array();
    for (const SequenceFrame& f : r.sequence)
      sequence.push_back({{"frame", f.frame}, {"time", f.time}, {"triangles", f.triangles},
                          {"moving_triangles", f.movingTriangles}, {"build_ms", f.buildMs}, {"frame_ms", f.frameMs},
                          {"total_ms", f.totalMs}, {"rays", f.rays}, {"mrays_per_s", f.mraysPerS}});
    j["sequence"] = sequence;
    j["dynamic"] = r.dynamic;
    j["static_build_ms"] = r.staticBuildMs;
  }
  // Only for DACRT: its work per frame, as the seed's Fig. 8 counts it.
  if (r.cone)
    j["cone"] = {{"half_angle_degrees", r.cone->degrees}, {"max_hits", r.cone->maxHits},
                 {"nodes_per_pixel", r.cone->nodesMean},  {"nodes_per_pixel_max", r.cone->nodesMax},
                 {"triangles_per_pixel", r.cone->trianglesMean}, {"triangles_per_pixel_max", r.cone->trianglesMax},
                 {"met_per_pixel", r.cone->metMean},      {"met_per_pixel_max", r.cone->metMax}};
  if (r.dacrt)
    j["dacrt"] = {{"ray_box_tests", r.dacrt->rayBox},           {"cone_box_tests", r.dacrt->coneBox},
                  {"triangle_box_tests", r.dacrt->triangleBox}, {"ray_triangle_tests", r.dacrt->rayTriangle},
                  {"nodes", r.dacrt->nodes}};
  j.update(toJson(r.structure));
  // Node (box) tests per ray for the roofline (scripts/bench_speed.py); null where not counted.
  j["node_tests_per_ray"] = orNull(nodeTestsPerRay(r));
  return j;
}

std::string summaryText(const RunReport& r, bool withStats) {
  if (!r.exported.empty())
    return format("%s: %zu triangles written to %s\n", r.scene.c_str(), r.triangles, r.exported.c_str());
  const AccelStats& s = r.structure;
  std::string text;
  if (!r.sequence.empty()) {
    double build = 0, total = 0;
    for (const SequenceFrame& f : r.sequence) build += f.buildMs, total += f.totalMs;
    const double n = double(r.sequence.size());
    text += format("%zu frames, time %g to %g, --dynamic %s: build %.1f ms + trace %.2f ms = T_F %.2f ms per frame "
                   "(means; static build %.1f ms once)\n",
                   r.sequence.size(), double(r.sequence.front().time), double(r.sequence.back().time),
                   r.dynamic.c_str(), build / n, r.frameMs, total / n, r.staticBuildMs);
  }
  if (withStats) {
    text += format("structure: %s, %zu nodes, %zu leaves, %zu triangle references, depth %u, %.2f floats/triangle\n",
                   s.name.c_str(), s.nodes, s.leaves, s.references, s.depth, s.floatsPerTriangle);
    text += format("build %.1f ms, SAH cost %s, memory %s\n", s.buildMs,
                   s.sahCost > 0 ? format("%.2f", s.sahCost).c_str() : "not computed",
                   s.structureBytes == 0    ? "not computed"
                   : s.structureBytes < 1e6 ? format("%.1f KB", double(s.structureBytes) / 1e3).c_str()
                                             : format("%.2f MB", double(s.structureBytes) / 1e6).c_str());
    text += format("per ray: %.2f traversal steps, %.2f triangle tests\n", r.stepsPerRay, r.triangleTestsPerRay);
    if (const std::optional<double> nodes = nodeTestsPerRay(r))
      text += format("node (box) tests per ray: %.2f\n", *nodes);
    text += format("max per pixel (all its rays): %llu traversal steps, %llu triangle tests\n",
                   static_cast<unsigned long long>(r.maxStepsPerRay),
                   static_cast<unsigned long long>(r.maxTriangleTestsPerRay));
    if (r.dacrt)
      text += format("dacrt per frame: %llu ray/box, %llu cone/box, %llu triangle/box, %llu ray/triangle tests, "
                     "%llu nodes\n",
                     (unsigned long long)r.dacrt->rayBox, (unsigned long long)r.dacrt->coneBox,
                     (unsigned long long)r.dacrt->triangleBox, (unsigned long long)r.dacrt->rayTriangle,
                     (unsigned long long)r.dacrt->nodes);
    if (r.cone)
      text += format("per cone (%g degrees): %.2f nodes (max %llu), %.2f triangles met in leaves (max %llu), "
                     "%.2f distinct triangles in the cone (max %llu)\n",
                     r.cone->degrees, r.cone->nodesMean, (unsigned long long)r.cone->nodesMax, r.cone->trianglesMean,
                     (unsigned long long)r.cone->trianglesMax, r.cone->metMean, (unsigned long long)r.cone->metMax);
  }
  text += format("%s: %zu triangles; %s renderer, %s (build %.1f ms, %.2f floats/triangle)%s%s\n", r.scene.c_str(),
                 r.triangles, r.renderer.c_str(), s.name.c_str(), s.buildMs, s.floatsPerTriangle,
                 r.glRenderer ? " on " : "", r.glRenderer ? r.glRenderer->c_str() : "");
  if (r.cone)  // one cone per pixel and no bounces: cones per second says more than Mrays/s
    text += format("%dx%d, %zu view(s): %.0f cones in %.2f ms per frame = %.0f cones/s\n", r.width, r.height, r.angles,
                   r.rays, r.frameMs, r.frameMs > 0 ? r.rays * 1000.0 / r.frameMs : 0.0);
  else
    text += format("%dx%d, %d bounces, %zu view(s): %.0f rays in %.2f ms per frame = %.3f Mrays/s (%.0f passes)\n",
                   r.width, r.height, r.bounces, r.angles, r.rays, r.frameMs, r.mraysPerS, r.passes);
  return text;
}

}  // namespace passtrace
