#pragma once
// The registry of acceleration structures: one row per structure, holding
// everything that identifies it. The command line (-a, --list, --help), the
// memory check, the JSON report, the tests and the benchmark scripts (through
// `passtrace --list --json`) all read this table; nothing else lists
// structures by hand. Adding a structure is one family folder under accel/
// (and kernels_glsl/) plus one row in registry.cpp.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel/cone/cone_traversal.h"
#include "accel/cpu_accelerator.h"
#include "accel/gpu_traversal.h"

namespace passtrace {

// The four renderers a run can use (-r), with tracy's ids.
enum class RendererId : int {
  OpenGl = 0,  // rasterized preview: no structure
  Cpu = 1,     // passtrace's CPU ray tracer
  Gpu = 2,     // the GPU stream ray tracer (fragment-pass kernels)
  Embree = 3   // the CPU ray tracer tracing through Intel Embree (the baseline)
};
inline constexpr RendererId kRenderers[] = {RendererId::OpenGl, RendererId::Cpu, RendererId::Gpu, RendererId::Embree};
// "opengl", "cpu", "gpu", "embree": the names of --list and the JSON report.
std::string_view rendererName(RendererId renderer);
// "OpenGL preview", "CPU", "GPU stream", "Embree": for messages.
std::string_view rendererTitle(RendererId renderer);

// A set of renderers, as bits 1 << id.
struct RendererSet {
  uint8_t bits = 0;
  constexpr RendererSet() = default;
  constexpr RendererSet(std::initializer_list<RendererId> renderers) {
    for (RendererId r : renderers) bits |= uint8_t(1u << int(r));
  }
  constexpr bool has(RendererId r) const { return bits & (1u << int(r)); }
};

// Build and traversal parameters a structure may read. A flag given on the
// command line that the chosen structure does not read is reported once as a
// warning (as pbrt-v4 reports unused parameters).
enum class BuildParam {
  SwapChildren,    // -c: K/K child swap probability (AccelBuildConfig::kayKajiya)
  GsTries,         // -t: Goldsmith/Salmon constructions (gsTries)
  GridMultiplier,  // -g: uniform grid resolution (gridMultiplier)
  KdMinElements,   // -e: kd-tree internal-node minimum (kdMinElements)
  KdMaxDepth,      // -d: kd-tree depth limit (kdMaxDepth)
  GridKernels,     // --grid-kernels: the GPU grid's merged or split kernels
  LoopLimit,       // -l: GPU traversal steps per pass (every stream structure)
  PageTexels,      // --page-texels: GPU data texture size (every stream structure)
  TriangleTest,    // --triangle-test: every structure but Embree
  KdStackSize,     // --stack-size: kd short-stack entries (kdStackSize)
  KdBuilder,       // --kd-builder: exact or binned SAH (kdBuilder)
  KdTermination,   // --kd-termination: thesis (-e/-d) or papay (kdTermination)
  Dynamic,         // --dynamic: a --frames sequence's strategy (kd rows, accel/kd/kd_dynamic.h)
  DacrtRLimit,     // --dacrt-rlimit: DACRT's ray count for naive tracing (dacrtRLimit)
  DacrtPLimit,     // --dacrt-plimit: DACRT's triangle count for naive tracing (dacrtPLimit)
  DacrtCones,      // --dacrt-cones: DACRT's conic packets (dacrtCones)
  DacrtSplit,      // --dacrt-split: DACRT's split position, mean or median (dacrtMedianSplit)
  BvhBuilder,      // --bvh-builder: the stack BVH's sah, sbvh or middle builder (bvhBuilder)
  Bvh8Builder,     // --bvh8-builder: the binned or sbvh binary tree bvh8 is collapsed from (bvh8Builder)
};
// The flag a parameter is given with, as --help shows it ("-g/--grid-multiplier").
std::string_view buildParamFlag(BuildParam param);
// Its default in the flag's own units ("1", "0 = 8 + 1.3 log2 N"), taken from
// the default-constructed AccelBuildConfig / GpuTraversalConfig.
std::string buildParamDefault(BuildParam param);
inline constexpr BuildParam kBuildParams[] = {
    BuildParam::SwapChildren,  BuildParam::GsTries,   BuildParam::GridMultiplier,
    BuildParam::KdMinElements, BuildParam::KdMaxDepth, BuildParam::GridKernels,
    BuildParam::LoopLimit,     BuildParam::PageTexels, BuildParam::TriangleTest,
    BuildParam::KdStackSize,   BuildParam::KdBuilder,  BuildParam::KdTermination,
    BuildParam::Dynamic,       BuildParam::DacrtRLimit, BuildParam::DacrtPLimit, BuildParam::DacrtCones,
    BuildParam::DacrtSplit, BuildParam::BvhBuilder,
    BuildParam::Bvh8Builder};

// Peak resident bytes of a run beyond the process's base, measured for the
// memory check (render/memory_check.h) by scripts/memory_models.py: the
// procedural "spheres" at 1 M and 4 M triangles,
//   passtrace -s spheres --triangles N -r R -a A -w 64 -b 1
// at the default thread count (GPU runs include llvmpipe's texture copies),
// less the same run at 1,000 triangles, fitted as c N^growth. Bytes 0 = not
// measured: the check then assumes the most any row of the renderer needs.
struct MemoryCost {
  double bytesPerTriangle = 0;  // at kMemoryModelTriangles
  // 1: linear. Above: bytes per triangle grow as (N / kMemoryModelTriangles)^(growth - 1)
  // (measured 1.00-1.11); not lowered below that size.
  double growth = 1;
  double bytesFor(uint64_t triangles) const;
};
inline constexpr double kMemoryModelTriangles = 4036802;  // --triangles 4000000

struct MemoryModel {
  MemoryCost cpu;  // on the CPU renderer (and Embree's)
  MemoryCost gpu;  // on the GPU stream renderer
};

using CpuFactory = std::unique_ptr<CpuAccelerator> (*)(std::span<const Triangle>, const AccelBuildConfig&);
using StreamFactory = std::unique_ptr<GpuTraversal> (*)(std::span<const Triangle>, const GpuTraversalConfig&);

enum class RayGrouping { None, Tiles, Generation };
std::string_view rayGroupingName(RayGrouping grouping);  // "none", "tiles", "generation"

// The benchmark reports that run a chosen few rows rather than every one:
// the scaling report (issue 36, scripts/bench_scale.py: the fastest CPU and
// stream rows and the baseline) and the fragment/compute stage table
// (issue 38, scripts/bench_stages.py and scripts/gpu_server/). A row says
// which feature it, on which renderer; the scripts read it from
// --list --json's "featured".
enum class Report { Scale, Stages };
std::string_view reportName(Report report);  // "scale", "stages"
struct Featured {
  Report report;
  RendererId renderer;
};

struct Structure {
  std::string_view name;         // -a NAME; also AccelStats::name of what it builds
  std::string_view family;       // its folder: accel/<family>/, kernels_glsl/<family>/
  std::string_view description;  // one line for --list and --help
  RendererSet renderers;         // the renderers that implement it
  // Thesis Table 4 number, and the renderers whose column gives it that
  // number (-r 2 -a 2 is kd-restart, -r 1 -a 2 is kd-tree).
  std::optional<int> number;
  RendererSet numberedOn;
  CpuFactory cpu = nullptr;        // -r 1 (and -r 3 for the Embree row)
  StreamFactory stream = nullptr;  // -r 2
  // The stream kernel's algorithm on the CPU over the same texels: counts the
  // same steps as the GPU (tests compare them). Null where there is none.
  CpuFactory mirror = nullptr;
  MemoryModel memory;
  std::vector<BuildParam> reads;  // besides the renderer's own (LoopLimit, PageTexels, TriangleTest)
  // How --stats counts node tests (the roofline's box tests: a BVH node's box,
  // a kd node's split plane, a grid or octree cell). By default a traversal
  // step is one node test or one triangle test, so node tests = steps -
  // triangle tests (every stream kernel and its mirror, the BVH traversals,
  // DACRT). True: the CPU traversal (-r 1) counts one step per node or cell
  // visited and tests a leaf's triangles inside that step, so node tests = steps.
  bool cpuStepsVisitNodes = false;
  // How the CPU traversal (-r 1) groups rays, which a ray's counts then depend
  // on: None, ray by ray; Tiles, packets of an image tile's pixels (counts
  // differ for rays grouped otherwise, e.g. the Python module's consecutive
  // rays); Generation, each generation as one batch (DACRT: an MPI run leaves
  // its frame whole rather than dividing its rows, render/session.cpp).
  // --list --json's "cpu_ray_groups".
  RayGrouping cpuRayGrouping = RayGrouping::None;
  // --cone: the structure's cone query on the CPU renderer (accel/cone/); null = none.
  ConeFactory cone = nullptr;
  // --cone with -r 2: the kd-tree the stream cone kernel walks (render/gpu_cone_tracer.h); null = none.
  ConeStreamFactory coneStream = nullptr;
  // The reports that feature this row (above); each renderer is one the row runs on.
  std::vector<Featured> featured = {};

  bool runsOn(RendererId r) const { return renderers.has(r); }
  // The parameters a run of this structure on `renderer` reads.
  std::vector<BuildParam> readsOn(RendererId renderer) const;
};

// Every structure, in the order of --list (thesis numbers first).
const std::vector<Structure>& structures();
// The row named `name`, or null.
const Structure* findStructure(std::string_view name);
// Resolves -a for a renderer: a name, or a thesis number in that renderer's
// column. Throws std::invalid_argument with one line listing the valid
// choices for that renderer. The OpenGL preview has none.
const Structure& resolveStructure(std::string_view nameOrNumber, RendererId renderer);

// Builds `s` for a renderer. Throw std::invalid_argument when `s` does not
// run there. The CPU ones hold a span of tris: keep the triangles alive.
std::unique_ptr<CpuAccelerator> makeCpuStructure(const Structure& s, std::span<const Triangle> tris,
                                                 const AccelBuildConfig& config = {});
std::unique_ptr<GpuTraversal> makeStreamStructure(const Structure& s, std::span<const Triangle> tris,
                                                  const GpuTraversalConfig& config = {});
std::unique_ptr<CpuAccelerator> makeMirrorStructure(const Structure& s, std::span<const Triangle> tris,
                                                    const AccelBuildConfig& config = {});
// Shorthands for tests and tools: resolveStructure + make.
std::unique_ptr<CpuAccelerator> makeCpuStructure(std::string_view nameOrNumber, std::span<const Triangle> tris,
                                                 const AccelBuildConfig& config = {});
std::unique_ptr<GpuTraversal> makeStreamStructure(std::string_view nameOrNumber, std::span<const Triangle> tris,
                                                  const GpuTraversalConfig& config = {});

// The flags in `given` that `s` on `renderer` does not read, in `given`'s order.
std::vector<BuildParam> unusedParams(const Structure& s, RendererId renderer, const std::vector<BuildParam>& given);

}  // namespace passtrace
