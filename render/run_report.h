#pragma once
// What one run measured, in one struct with one JSON writer (--json) and one
// text summary (stdout). schema_version counts changes to the JSON's keys;
// every key of schema 1 kept its name and meaning.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>  // the whole of it in run_report.cpp: a heavy parse

#include "accel/cpu_accelerator.h"

namespace passtrace {

inline constexpr int kRunReportSchemaVersion = 3;  // 2: schema_version, version, warnings; 3: ranks, rank_runs

// One frame of a --frames sequence: the scene at `time`, rebuilt and traced.
struct SequenceFrame {
  size_t frame = 0;
  float time = 0;
  size_t triangles = 0, movingTriangles = 0;
  double buildMs = 0, frameMs = 0, rays = 0, mraysPerS = 0;
  double totalMs = 0;  // buildMs + frameMs: the seed's T_F
};

struct FrameReport {
  size_t angle = 0;
  double frameMs = 0;
  uint64_t rays = 0;
  uint64_t passes = 0;
};

// One MPI rank's part of a run (render/ranks.h); a single process is rank 0 of 1.
struct RankRun {
  int rank = 0;
  std::string host;
  double buildMs = 0;  // its structure builds (every frame's in a sequence)
  double traceMs = 0;  // its own renders, summed over its repeats
  size_t share = 0;    // angles, sequence frames, or a frame's rows it rendered
};

// --cone runs: per pixel (one cone each) over the angles' fastest repeats.
struct ConeReport {
  double degrees = 0;       // half-angle
  uint32_t maxHits = 0;     // --cone-max (0 = all)
  double nodesMean = 0, trianglesMean = 0, metMean = 0;  // nodes visited, triangle references met, count
  uint64_t nodesMax = 0, trianglesMax = 0, metMax = 0;
};

struct RunReport {
  std::string version;                 // passtrace's
  std::string scene;
  size_t triangles = 0;
  std::string exported;  // --export: the file written instead of rendering
  std::string renderer;                // rendererName()
  int rendererId = 0;
  AccelStats structure;                // name "none" for the preview
  std::optional<int> structureNumber;  // thesis number in the renderer's column
  std::optional<std::string> triangleTest;  // null for the preview; "embree" for Embree
  int width = 0, height = 0, bounces = 0, repeats = 0;
  size_t angles = 0;
  // Means over the angles of each angle's fastest repeat.
  double rays = 0, frameMs = 0, mraysPerS = 0, passes = 0, steps = 0, triangleTests = 0;
  double stepsPerRay = 0, triangleTestsPerRay = 0;
  // Structure::cpuStepsVisitNodes of the run (-r 1 only): how nodeTestsPerRay() reads steps.
  bool stepsVisitNodes = false;
  // The most of one pixel's rays over the frames (FrameStats::maxStepsPerRay).
  uint64_t maxStepsPerRay = 0, maxTriangleTestsPerRay = 0;
  std::optional<std::string> glRenderer, glBackend;  // GL runs only
  std::vector<FrameReport> frames;
  std::vector<SequenceFrame> sequence;  // --frames: one entry per frame of the sequence
  std::string dynamic;         // --frames: the --dynamic strategy
  double staticBuildMs = 0;    // --frames: the one-time static tree build (two-trees, merge; 0 for rebuild)
  std::vector<std::string> warnings;  // also printed on stderr unless --quiet
  // DACRT's filter counters per frame (means over the angles or frames):
  // the JSON's "dacrt" object, only in runs of a batch tracer.
  std::optional<FilterStats> dacrt;
  std::string shading = "thesis";  // --shading: thesis, whitted or ao
  std::optional<std::string> stage;  // --stage: fragment or compute (-r 2 only; null elsewhere)
  std::string compact = "off";     // --compact: off, on or always (-r 2 only; off elsewhere)
  std::optional<ConeReport> cone;  // --cone: the JSON's "cone" object
  int ranks = 1;                   // MPI ranks the run was divided among (render/ranks.h)
  std::vector<RankRun> rankRuns;   // each rank's host and times, in rank order
  // The picture -o writes (the first angle's, or a sequence's first frame):
  // width*height*3 floats, row 0 the top row. Not in the JSON; empty for
  // --cone and --export runs, which render no image.
  std::vector<float> image;
};

nlohmann::json toJson(const RunReport& report);
// The report's keys that describe the structure (accelerator, build_ms,
// accel_*, structure): also the Python module's Accelerator.stats().
nlohmann::json toJson(const AccelStats& stats);
// Node tests per ray (the roofline's box tests; Structure::cpuStepsVisitNodes
// says how steps read); null for Embree, which counts nothing, and the preview.
std::optional<double> nodeTestsPerRay(const RunReport& report);
// The two summary lines (three with `withStats`) passtrace prints.
std::string summaryText(const RunReport& report, bool withStats);

}  // namespace passtrace
