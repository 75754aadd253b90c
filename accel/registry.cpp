#include "accel/registry.h"

#include <cmath>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "accel/bih/bih_structures.h"
#include "accel/bvh/bvh_structures.h"
#include "accel/bvh_stack/bvh_stack_structure.h"
#include "accel/dacrt/dacrt_structure.h"
#include "accel/grid/grid_structures.h"
#include "accel/kd/kd_structures.h"
#include "accel/kd/kd_ropes_structures.h"
#include "accel/octree/octree_structure.h"
#include "accel/wide_bvh/wide_bvh_structure.h"
#if PASSTRACE_HAVE_EMBREE
#include "accel/embree/embree_accelerator.h"
#endif

namespace passtrace {
namespace {

using enum RendererId;
using P = BuildParam;

// One row per structure. Memory: bytes per triangle and growth measured by
// scripts/memory_models.py as registry.h's MemoryModel says (2026-11-28, two
// threads; docs/measurements.md; the CPU column of kd-restart, kd-backtrack
// and grid-stream is their kernels' CPU mirrors). dacrt's grows with the
// threads: each running band holds 4 bytes of triangle index per triangle.
std::vector<Structure> makeRows() {
  std::vector<Structure> rows = {
      {.name = "kk-bvh", .family = "bvh",
       .description = "Kay/Kajiya BVH (SAH-ordered splits), walked as its escape-index sequence",
       .renderers = {Cpu, Gpu}, .number = 0, .numberedOn = {Cpu, Gpu},
       .cpu = makeKkBvhCpu, .stream = makeKkBvhStream, .mirror = makeKkBvhCpu,
       .memory = {.cpu = {221, 1.03}, .gpu = {217, 1.06}}, .reads = {P::SwapChildren}, .cone = makeKkBvhCone,
       // In the scaling report the compact stream row: it traces 50 M triangles where others do not fit.
       .coneStream = makeKkBvhStreamCone, .featured = {{Report::Scale, Gpu}, {Report::Stages, Gpu}}},
      {.name = "gs-bvh", .family = "bvh",
       .description = "Goldsmith/Salmon BVH (insertion build), walked as its escape-index sequence",
       .renderers = {Cpu, Gpu}, .number = 1, .numberedOn = {Cpu, Gpu},
       .cpu = makeGsBvhCpu, .stream = makeGsBvhStream, .mirror = makeGsBvhCpu,
       .memory = {.cpu = {460, 1.01}, .gpu = {456, 1.05}}, .reads = {P::GsTries},
       .featured = {{Report::Stages, Gpu}}},
      {.name = "kd-tree", .family = "kd",
       .description = "kd-tree, SAH with split clipping, stack traversal",
       .renderers = {Cpu}, .number = 2, .numberedOn = {Cpu},
       .cpu = makeKdTreeCpu,
       .memory = {.cpu = {559}}, .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination, P::Dynamic},
       .cpuStepsVisitNodes = true, .cone = makeKdTreeCone},
      {.name = "kd-pbrt", .family = "kd",
       .description = "kd-tree built the pbrt way (pbrt's constants), stack traversal",
       .renderers = {Cpu}, .number = 3, .numberedOn = {Cpu},
       .cpu = makeKdPbrtCpu,
       .memory = {.cpu = {3548}}, .reads = {P::KdMaxDepth}, .cpuStepsVisitNodes = true, .cone = makeKdPbrtCone},
      {.name = "grid", .family = "grid",
       .description = "uniform grid: 3D-DDA on the CPU, stream kernels on the GPU (--grid-kernels)",
       .renderers = {Cpu, Gpu}, .number = 4, .numberedOn = {Cpu, Gpu},
       .cpu = makeGridCpu, .stream = makeGridStream, .mirror = makeGridStreamMirror,
       .memory = {.cpu = {1162}, .gpu = {1273}},
       .reads = {P::GridMultiplier, P::GridKernels}, .cpuStepsVisitNodes = true},
      {.name = "kk-bvh-recursive", .family = "bvh",
       .description = "Kay/Kajiya BVH descended recursively",
       .renderers = {Cpu}, .number = 5, .numberedOn = {Cpu},
       .cpu = makeKkBvhRecursiveCpu,
       .memory = {.cpu = {157, 1.04}}, .reads = {P::SwapChildren}},
      {.name = "gs-bvh-recursive", .family = "bvh",
       .description = "Goldsmith/Salmon BVH descended recursively",
       .renderers = {Cpu}, .number = 6, .numberedOn = {Cpu},
       .cpu = makeGsBvhRecursiveCpu,
       .memory = {.cpu = {469, 1.02}}, .reads = {P::GsTries}},
      // The thesis's octree traversal keeps number 7 (it was the row "octree"
      // before Revelles' traversal took that name, see the row "octree" below).
      {.name = "octree-descent", .family = "octree",
       .description = "octree, front-to-back descent with box tests (the thesis's)",
       .renderers = {Cpu}, .number = 7, .numberedOn = {Cpu},
       .cpu = makeOctreeDescentCpu,
       .memory = {.cpu = {172, 1.04}}, .reads = {}, .cpuStepsVisitNodes = true},
      {.name = "kd-restart", .family = "kd",
       .description = "kd-tree, stackless kd-restart (Foley & Sugerman); on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = 2, .numberedOn = {Gpu},
       .cpu = makeKdRestartMirror, .stream = makeKdRestartStream, .mirror = makeKdRestartMirror,
       .memory = {.cpu = {698}, .gpu = {639}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination, P::Dynamic}},
      {.name = "kd-backtrack", .family = "kd",
       .description = "kd-tree, stackless kd-backtrack (parent links); on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = 3, .numberedOn = {Gpu},
       .cpu = makeKdBacktrackMirror, .stream = makeKdBacktrackStream, .mirror = makeKdBacktrackMirror,
       .memory = {.cpu = {826}, .gpu = {809, 1.01}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination, P::Dynamic}},
      // Seed 003 ch. 6 (Horn et al. 2007), over kd-restart's tree and texels.
      // Memory measured for kd-pushdown and kd-stack (both 416 / 383; kd-restart
      // measured 416 / 383 in the same session); the short stacks hold the same
      // data plus a record of 4 + 3K floats per pixel.
      {.name = "kd-pushdown", .family = "kd",
       .description = "kd-tree, restart from the push-down root (Horn et al.); on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdStreamMirror<KdStreamVariant::PushDown>,
       .stream = makeKdStream<KdStreamVariant::PushDown>,
       .mirror = makeKdStreamMirror<KdStreamVariant::PushDown>,
       .memory = {.cpu = {692}, .gpu = {647}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination, P::Dynamic}},
      {.name = "kd-shortstack", .family = "kd",
       .description = "kd-tree, circular short stack (--stack-size), restart when empty; on the CPU the kernel's "
                      "algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdStreamMirror<KdStreamVariant::ShortStack>,
       .stream = makeKdStream<KdStreamVariant::ShortStack>,
       .mirror = makeKdStreamMirror<KdStreamVariant::ShortStack>,
       .memory = {.cpu = {699}, .gpu = {641}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination,
                                         P::KdStackSize, P::Dynamic}},
      {.name = "kd-pushdown-shortstack", .family = "kd",
       .description = "kd-tree, short stack restarting from the push-down root; on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdStreamMirror<KdStreamVariant::PushDownShortStack>,
       .stream = makeKdStream<KdStreamVariant::PushDownShortStack>,
       .mirror = makeKdStreamMirror<KdStreamVariant::PushDownShortStack>,
       .memory = {.cpu = {692}, .gpu = {627, 1.03}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination,
                                         P::KdStackSize, P::Dynamic}},
      {.name = "kd-stack", .family = "kd",
       .description = "kd-tree, full stack (as deep as the tree) in a per-ray storage buffer; on the CPU the "
                      "kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdStreamMirror<KdStreamVariant::Stack>,
       .stream = makeKdStream<KdStreamVariant::Stack>,
       .mirror = makeKdStreamMirror<KdStreamVariant::Stack>,
       .memory = {.cpu = {698}, .gpu = {662}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination, P::Dynamic},
       .coneStream = makeKdTreeStreamCone},
      {.name = "grid-stream", .family = "grid",
       .description = "the GPU uniform-grid kernel's algorithm over its texels, on the CPU",
       .renderers = {Cpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeGridStreamMirror,
       .memory = {.cpu = {1274}}, .reads = {P::GridMultiplier}},
      {.name = "dacrt", .family = "dacrt",
       .description = "divide-and-conquer ray tracing (Mora 2011): no stored structure, rays and triangles "
                      "filtered together each frame",
       .renderers = {Cpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeDacrtCpu,
       .memory = {.cpu = {62, 1.09}}, .reads = {P::DacrtRLimit, P::DacrtPLimit, P::DacrtCones, P::DacrtSplit},
       .cpuRayGrouping = RayGrouping::Generation},
      // Seed 002: kd-restart's tree with ropes (Popov et al. 2007). Memory measured for kd-ropes and kd-compact
      // in one session in which kd-stack measured 693 bytes per triangle on the CPU.
      {.name = "kd-ropes", .family = "kd",
       .description = "kd-tree with six ropes per leaf, stackless from the entry point; on the CPU the kernel's "
                      "algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdRopesMirror, .stream = makeKdRopesStream, .mirror = makeKdRopesMirror,
       .memory = {.cpu = {883}, .gpu = {835}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination}},
      // Seed 002's standard kd traversal: kd-stack over 8-byte nodes (kd_compact_node.h).
      {.name = "kd-compact", .family = "kd",
       .description = "kd-tree, full stack as kd-stack over compact 8-byte nodes; on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeKdStreamMirror<KdStreamVariant::Compact>,
       .stream = makeKdStream<KdStreamVariant::Compact>,
       .mirror = makeKdStreamMirror<KdStreamVariant::Compact>,
       .memory = {.cpu = {667}, .gpu = {605}},
       .reads = {P::KdMinElements, P::KdMaxDepth, P::KdBuilder, P::KdTermination}},
      // Seed 002 (Aila & Laine 2009); the CPU row runs the kernel's algorithm.
      {.name = "bvh-stack", .family = "bvh_stack",
       .description = "binary BVH (--bvh-builder sah, sbvh or middle), two child boxes per node, stack traversal "
                      "nearer child first; on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeBvhStackCpu, .stream = makeBvhStackStream, .mirror = makeBvhStackCpu,
       .memory = {.cpu = {260, 1.06}, .gpu = {217, 1.11}},
       .reads = {P::BvhBuilder}},  // measured with the default sah build
      // Wächter & Keller 2006; the CPU runs the kernel's algorithm (bih_structures.h).
      {.name = "bih", .family = "bih",
       .description = "bounding interval hierarchy (two clip planes per node, global-box splits), stack traversal; "
                      "on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeBihCpu, .stream = makeBihStream, .mirror = makeBihCpu,
       .memory = {.cpu = {150, 1.04}, .gpu = {165, 1.05}}, .reads = {}},
      // Revelles et al. 2000 (not in the thesis, so unnumbered: -r 1 -a 7 runs
      // what it always ran, the descent above).
      {.name = "octree", .family = "octree",
       .description = "octree, Revelles et al.'s parametric traversal; on the CPU the kernel's algorithm",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeOctreeCpu, .stream = makeOctreeStream, .mirror = makeOctreeCpu,
       .memory = {.cpu = {273, 1.02}, .gpu = {309, 1.05}}, .reads = {}},
      {.name = "bvh8", .family = "wide_bvh",
       .description = "8-wide BVH collapsed from a binned SAH BVH (built on all cores; --bvh8-builder sbvh: with "
                      "spatial splits), AVX2 node and triangle tests",
       .renderers = {Cpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeBvh8Cpu,
       // The larger of the two builders' models, so the check holds for either: binned {131, 1.04},
       // --bvh8-builder sbvh 168 at 1 M and 134 at 4 M triangles.
       .memory = {.cpu = {168}}, .reads = {P::Bvh8Builder}, .featured = {{Report::Scale, Cpu}}},
      {.name = "bvh8-packet", .family = "wide_bvh",
       .description = "bvh8 traced in packets: primary rays 32 at a time (8x4 pixels), shadow and AO rays up to 64 "
                      "(8x8); over trees larger than 16 MiB eight tiles' packets at once, taking turns to hide cache "
                      "misses",
       .renderers = {Cpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeBvh8PacketCpu,
       .memory = {.cpu = {168}}, .reads = {P::Bvh8Builder}, .cpuRayGrouping = RayGrouping::Tiles,  // as bvh8
       .featured = {{Report::Scale, Cpu}}},
      // Issue 17 item 3: kk-bvh's kernel over eight child orders (Hachisuka's MTBVH, one order per octant) of
      // bvh-stack's tree.
      {.name = "bvh-octant", .family = "bvh",
       .description = "binary BVH (--bvh-builder) as eight escape-index sequences, children near-first for each "
                      "ray octant (no per-ray stack; boxes of one texel on a scene-wide grid, the triangles stored "
                      "once for the eight); on the CPU the kernel's algorithm over the same texels",
       .renderers = {Cpu, Gpu}, .number = std::nullopt, .numberedOn = {},
       .cpu = makeOctantBvhCpu, .stream = makeOctantBvhStream, .mirror = makeOctantBvhCpu,
       // The GPU's (fused too) with boxes of one quantized texel and one-texel leaves over a shared triangle
       // stream, written from octant 0's sequence once the tree is freed; --bvh-builder sbvh's (361 at
       // 1 M, 368 at 4 M; the default's 366). The steps that got it there: docs/measurements.md.
       .memory = {.cpu = {491}, .gpu = {368}}, .reads = {P::BvhBuilder}, .featured = {{Report::Stages, Gpu}}},
      // Issue 17 item 3, fewer passes per bounce: bvh-octant's walk with ray generation and shading in one pass.
      {.name = "bvh-octant-fused", .family = "bvh",
       .description = "bvh-octant on the stream path with a primary bounce in one pass: ray generation, the "
                      "octant walk and thesis shading fused, at -l 0 (other bounces, shadings and -l pass by pass)",
       .renderers = {Gpu}, .number = std::nullopt, .numberedOn = {},
       .stream = makeOctantBvhFusedStream, .mirror = makeOctantBvhCpu,
       .memory = {.gpu = {368}}, .reads = {P::BvhBuilder},  // bvh-octant's data and the fused pass
       .featured = {{Report::Scale, Gpu}, {Report::Stages, Gpu}}},
  };
#if PASSTRACE_HAVE_EMBREE
  rows.push_back({.name = "embree", .family = "embree",
                  .description = "Intel Embree 3 (rtcIntersect16/rtcOccluded16 packets of primary and shadow "
                                 "rays, 8 or 4 wide without AVX-512; rtcIntersect1 otherwise), the baseline, "
                                 "through the CPU renderer",
                  .renderers = {Embree}, .number = std::nullopt, .numberedOn = {},
                  .cpu = makeEmbreeCpu,
                  .memory = {.cpu = {192, 1.02}}, .reads = {}, .featured = {{Report::Scale, Embree}}});
#endif
  return rows;
}

std::string numberText(int number) { return std::to_string(number); }

}  // namespace

std::string_view reportName(Report report) {
  switch (report) {
    case Report::Scale: return "scale";
    case Report::Stages: return "stages";
  }
  return "?";
}

std::string_view rendererName(RendererId renderer) {
  switch (renderer) {
    case OpenGl: return "opengl";
    case Cpu: return "cpu";
    case Gpu: return "gpu";
    case Embree: return "embree";
  }
  return "?";
}

std::string_view rayGroupingName(RayGrouping grouping) {
  switch (grouping) {
    case RayGrouping::None: return "none";
    case RayGrouping::Tiles: return "tiles";
    case RayGrouping::Generation: return "generation";
  }
  return "?";
}

double MemoryCost::bytesFor(uint64_t triangles) const {
  const double n = double(triangles);
  return bytesPerTriangle * n * std::pow(std::max(1.0, n / kMemoryModelTriangles), growth - 1);
}

std::string_view rendererTitle(RendererId renderer) {
  switch (renderer) {
    case OpenGl: return "OpenGL preview";
    case Cpu: return "CPU";
    case Gpu: return "GPU stream";
    case Embree: return "Embree";
  }
  return "?";
}

std::string_view buildParamFlag(BuildParam param) {
  switch (param) {
    case P::SwapChildren: return "-c/--swap-children";
    case P::GsTries: return "-t/--gs-tries";
    case P::GridMultiplier: return "-g/--grid-multiplier";
    case P::KdMinElements: return "-e/--kd-min-elements";
    case P::KdMaxDepth: return "-d/--kd-max-depth";
    case P::GridKernels: return "--grid-kernels";
    case P::LoopLimit: return "-l/--loop-limit";
    case P::PageTexels: return "--page-texels";
    case P::TriangleTest: return "--triangle-test";
    case P::KdStackSize: return "--stack-size";
    case P::KdBuilder: return "--kd-builder";
    case P::KdTermination: return "--kd-termination";
    case P::Dynamic: return "--dynamic";
    case P::DacrtRLimit: return "--dacrt-rlimit";
    case P::DacrtPLimit: return "--dacrt-plimit";
    case P::DacrtCones: return "--dacrt-cones";
    case P::DacrtSplit: return "--dacrt-split";
    case P::BvhBuilder: return "--bvh-builder";
    case P::Bvh8Builder: return "--bvh8-builder";
  }
  return "?";
}

std::string buildParamDefault(BuildParam param) {
  const GpuTraversalConfig gpu;
  const AccelBuildConfig& cpu = gpu.build;
  // Shortest decimal that reads back as the value: "1", "0.5".
  const auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return std::string(buf);
  };
  switch (param) {
    case P::SwapChildren: return number(2.0 * cpu.kayKajiya.swapProbability);  // -c is tracy's: twice the probability
    case P::GsTries: return number(cpu.gsTries);
    case P::GridMultiplier: return number(cpu.gridMultiplier);
    case P::KdMinElements: return number(cpu.kdMinElements);
    case P::KdMaxDepth: return cpu.kdMaxDepth == 0 ? "0 = 8 + 1.3 log2 N" : number(cpu.kdMaxDepth);
    case P::GridKernels: return gpu.gridKernels == GridKernels::Merged ? "merged" : "split";
    case P::LoopLimit: return gpu.loopLimit == 0 ? "0 = one pass per bounce (within the driver's loop cap)"
                                                  : number(gpu.loopLimit);
    case P::PageTexels: return gpu.maxPageTexels == 0 ? "0 = the largest texture" : number(double(gpu.maxPageTexels));
    case P::TriangleTest: return kTriangleTestNames[int(cpu.triangleTest)];
    case P::KdStackSize: return number(cpu.kdStackSize);
    case P::KdBuilder: return std::string(kKdBuilderNames[int(cpu.kdBuilder)]);
    case P::KdTermination: return std::string(kKdTerminationNames[int(cpu.kdTermination)]);
    case P::Dynamic: return "rebuild";
    case P::DacrtRLimit: return number(cpu.dacrtRLimit);
    case P::DacrtPLimit: return number(cpu.dacrtPLimit);
    case P::DacrtCones: return cpu.dacrtCones ? "on" : "off";
    case P::DacrtSplit: return cpu.dacrtMedianSplit ? "median" : "mean";
    case P::BvhBuilder: return std::string(kBvhBuilderNames[int(cpu.bvhBuilder)]);
    case P::Bvh8Builder: return std::string(kBvh8BuilderNames[int(cpu.bvh8Builder)]);
  }
  return "?";
}

std::vector<BuildParam> Structure::readsOn(RendererId renderer) const {
  std::vector<BuildParam> params;
  if (!runsOn(renderer)) return params;
  for (BuildParam p : reads)
    if (p != P::GridKernels || renderer == Gpu) params.push_back(p);  // only the GPU grid has kernels to choose
  if (renderer == Gpu) params.insert(params.end(), {P::LoopLimit, P::PageTexels});
  if (renderer != Embree) params.push_back(P::TriangleTest);
  return params;
}

const std::vector<Structure>& structures() {
  static const std::vector<Structure> rows = makeRows();
  return rows;
}

const Structure* findStructure(std::string_view name) {
  for (const Structure& s : structures())
    if (s.name == name) return &s;
  return nullptr;
}

const Structure& resolveStructure(std::string_view nameOrNumber, RendererId renderer) {
  for (const Structure& s : structures()) {
    if (!s.runsOn(renderer)) continue;
    if (s.name == nameOrNumber) return s;
    if (s.number && s.numberedOn.has(renderer) && numberText(*s.number) == nameOrNumber) return s;
  }
  // The valid choices, numbered ones in number order first.
  std::vector<const Structure*> valid;
  for (const Structure& s : structures())
    if (s.runsOn(renderer)) valid.push_back(&s);
  if (valid.empty())
    throw std::invalid_argument("the " + std::string(rendererTitle(renderer)) + " renderer uses no structure");
  const auto numberOn = [&](const Structure* s) {
    return s->number && s->numberedOn.has(renderer) ? *s->number : 1 << 30;
  };
  std::stable_sort(valid.begin(), valid.end(),
                   [&](const Structure* a, const Structure* b) { return numberOn(a) < numberOn(b); });
  std::string list;
  for (const Structure* s : valid) {
    list += list.empty() ? "" : ", ";
    if (numberOn(s) != 1 << 30) list += numberText(*s->number) + " ";
    list += s->name;
  }
  const std::string title(rendererTitle(renderer));
  if (findStructure(nameOrNumber))
    throw std::invalid_argument("accelerator '" + std::string(nameOrNumber) + "' does not run on the " + title +
                                " renderer (valid: " + list + ")");
  throw std::invalid_argument("unknown accelerator '" + std::string(nameOrNumber) + "' (valid on the " + title +
                              " renderer: " + list + ")");
}

std::unique_ptr<CpuAccelerator> makeCpuStructure(const Structure& s, std::span<const Triangle> tris,
                                                 const AccelBuildConfig& config) {
  if (!s.cpu) throw std::invalid_argument(std::string(s.name) + " has no CPU implementation");
  return s.cpu(tris, config);
}

std::unique_ptr<GpuTraversal> makeStreamStructure(const Structure& s, std::span<const Triangle> tris,
                                                  const GpuTraversalConfig& config) {
  if (!s.stream) throw std::invalid_argument(std::string(s.name) + " has no GPU stream implementation");
  if (config.loopLimit < 0) throw std::invalid_argument("the loop limit (-l) must be at least 0");
  return s.stream(tris, withPassStepLimit(config));
}

std::unique_ptr<CpuAccelerator> makeMirrorStructure(const Structure& s, std::span<const Triangle> tris,
                                                    const AccelBuildConfig& config) {
  if (!s.mirror) throw std::invalid_argument(std::string(s.name) + " has no CPU mirror of a stream kernel");
  return s.mirror(tris, config);
}

std::unique_ptr<CpuAccelerator> makeCpuStructure(std::string_view nameOrNumber, std::span<const Triangle> tris,
                                                 const AccelBuildConfig& config) {
  return makeCpuStructure(resolveStructure(nameOrNumber, Cpu), tris, config);
}

std::unique_ptr<GpuTraversal> makeStreamStructure(std::string_view nameOrNumber, std::span<const Triangle> tris,
                                                  const GpuTraversalConfig& config) {
  return makeStreamStructure(resolveStructure(nameOrNumber, Gpu), tris, config);
}

std::vector<BuildParam> unusedParams(const Structure& s, RendererId renderer, const std::vector<BuildParam>& given) {
  const std::vector<BuildParam> read = s.readsOn(renderer);
  std::vector<BuildParam> unused;
  for (BuildParam p : given)
    if (std::find(read.begin(), read.end(), p) == read.end()) unused.push_back(p);
  return unused;
}

}  // namespace passtrace
