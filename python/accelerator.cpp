#include "python/accelerator.h"

#include <algorithm>
#include <optional>

#include <pybind11/numpy.h>
#include <tbb/task_arena.h>

#include "apps/run_settings.h"
#include "python/flag_arguments.h"
#include "python/gl_thread.h"
#include "python/json_value.h"
#include "python/ray_arrays.h"
#include "render/ray_query.h"
#include "render/run_report.h"
#include "render/stream_ray_query.h"

namespace passtrace::python {

namespace {

// "-g/--grid-multiplier" -> "grid_multiplier"
std::string keywordOf(BuildParam p) {
  std::string flag(buildParamFlag(p));
  flag = flag.substr(flag.rfind("--") + 2);
  std::replace(flag.begin(), flag.end(), '-', '_');
  return flag;
}

RendererId rendererOf(const std::string& name, const std::string& structure) {
  if (name == "gpu") return RendererId::Gpu;
  if (name == "embree") return RendererId::Embree;
  if (name == "cpu") {
    // Embree's row is a CPU structure too (the CPU renderer traces through it).
    const Structure* row = findStructure(structure);
    return row && !row->runsOn(RendererId::Cpu) && row->runsOn(RendererId::Embree) ? RendererId::Embree
                                                                                    : RendererId::Cpu;
  }
  throwValueError("renderer: '" + name + "' is not one of cpu, gpu, embree");
}

}  // namespace

std::vector<std::string> buildParameterNames() {
  std::vector<std::string> names;
  for (BuildParam p : kBuildParams)
    if (p != BuildParam::Dynamic) names.push_back(keywordOf(p));  // --dynamic is a --frames sequence's: render()
  names.push_back("threads");
  names.push_back("stage");
  return names;
}

Accelerator::Accelerator(std::shared_ptr<const Scene> scene, const std::string& structure, const std::string& renderer,
                         const py::dict& params)
    : scene_(std::move(scene)) {
  renderer_ = rendererOf(renderer, structure);
  const std::vector<std::string> known = buildParameterNames();
  for (const auto& [key, value] : params) {
    const std::string name = key.cast<std::string>();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throwValueError("build: '" + name + "' is not a build or traversal parameter (they are: " + list + ")");
    }
    if (name == "stage" && renderer_ != RendererId::Gpu) throwValueError("--stage is read by the gpu renderer only");
  }
  std::vector<std::string> args = {"--renderer=" + std::to_string(int(renderer_)), "--accel=" + structure};
  const std::vector<std::string> given = flagArguments(params);
  args.insert(args.end(), given.begin(), given.end());
  RunSettings settings;
  try {
    settings = toRunSettings(parseFlags(args));
    row_ = renderer_ == RendererId::Embree ? findStructure("embree") : &resolveStructure(structure, renderer_);
    if (!row_) throw std::runtime_error("this passtrace was built without Embree (renderer embree is not available)");
    if (renderer_ == RendererId::Embree && structure != "embree" && findStructure(structure) != row_)
      throw std::runtime_error("renderer embree builds the embree row only, not '" + structure + "'");
  } catch (const py::value_error&) {
    throw;
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
  for (BuildParam p : unusedParams(*row_, renderer_, settings.givenParams))
    throwValueError(std::string(buildParamFlag(p)) + " is not read by " + std::string(row_->name) + " on the " +
                    std::string(rendererTitle(renderer_)) + " renderer");
  threads_ = settings.threads;
  stage_ = settings.gpu.stage;

  py::gil_scoped_release released;
  const std::span<const Triangle> tris = scene_->triangles;
  if (renderer_ == RendererId::Gpu) {
    runOnGlThread([&] {
      const StreamStageScope stage(stage_);
      gpu_ = makeStreamStructure(*row_, tris, withPassStepLimit(settings.gpu));
      query_ = std::make_unique<StreamRayQuery>(*gpu_);
      stats_ = gpu_->stats();
    });
  } else {
    // --threads caps the build's oneTBB tasks as it caps the program's.
    tbb::task_arena arena(threads_ ? int(threads_) : tbb::task_arena::automatic);
    arena.execute([&] { cpu_ = makeCpuStructure(*row_, tris, settings.gpu.build); });
    stats_ = cpu_->stats();
  }
}

Accelerator::Accelerator(std::shared_ptr<const Scene> scene) : scene_(std::move(scene)) {}

std::unique_ptr<Accelerator> Accelerator::bruteForce(std::shared_ptr<const Scene> scene, const std::string& triangleTest) {
  const std::optional<TriangleTest> test = triangleTestByName(triangleTest);
  if (!test) throwValueError("triangle_test: '" + triangleTest + "' is not moller-trumbore or watertight");
  std::unique_ptr<Accelerator> a(new Accelerator(std::move(scene)));
  a->cpu_ = makeBruteForceAccelerator(a->scene_->triangles, *test);
  a->stats_ = a->cpu_->stats();
  return a;
}

Accelerator::~Accelerator() {
  if (!gpu_) return;
  py::gil_scoped_release released;
  runOnGlThread([&] {
    query_.reset();
    gpu_.reset();
  });
}

void Accelerator::trace(const std::vector<Ray>& rays, bool anyHit, std::vector<Hit>& hits,
                        std::vector<RayStats>* stats) {
  hits.resize(rays.size());
  if (stats) stats->resize(rays.size());
  py::gil_scoped_release released;
  if (gpu_) {
    runOnGlThread([&] {
      const StreamStageScope stage(stage_);
      const std::vector<uint8_t> shadow(anyHit ? rays.size() : 0, 1);
      query_->trace(rays, shadow, hits, stats ? std::span<RayStats>(*stats) : std::span<RayStats>());
    });
  } else {
    traceRays(*cpu_, rays, anyHit, hits, stats ? std::span<RayStats>(*stats) : std::span<RayStats>(), threads_);
  }
}

py::dict Accelerator::intersect(const py::handle& origins, const py::handle& directions, const py::handle& tmax,
                                bool counters) {
  const RayArrays in = readRays(origins, directions, tmax, scene_->scaleExponent);
  std::vector<Hit> hits;
  std::vector<RayStats> stats;
  trace(in.rays, false, hits, counters ? &stats : nullptr);
  return hitArrays(hits, counters ? &stats : nullptr, in.shape, scene_->scaleExponent);
}

py::object Accelerator::occluded(const py::handle& origins, const py::handle& directions, const py::handle& tmax) {
  const RayArrays in = readRays(origins, directions, tmax, scene_->scaleExponent);
  std::vector<Hit> hits;
  trace(in.rays, true, hits, nullptr);
  return foundArray(hits, in.shape);
}

py::dict Accelerator::stats() const { return jsonValue(toJson(stats_)); }

std::string Accelerator::repr() const {
  return "<passtrace.Accelerator " + (row_ ? std::string(row_->name) : stats_.name) + " on " + std::string(rendererName(renderer_)) + ", " +
         std::to_string(scene_->triangles.size()) + " triangles>";
}

}  // namespace passtrace::python
