#include "apps/cli_options.h"

#include <charconv>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <utility>

#include <CLI/CLI.hpp>

namespace passtrace {
namespace {

// --help's groups, in the order they are printed.
constexpr const char* kSceneGroup = "Scene and camera";
constexpr const char* kOutputGroup = "Image and outputs";
constexpr const char* kStructureGroup = "Renderer and structure";
constexpr const char* kBuildGroup = "Build parameters (each structure reads its own; --list says which)";
constexpr const char* kShadingGroup = "Shading and ray mixes";
constexpr const char* kStreamGroup = "GPU stream path (-r 2)";
constexpr const char* kSequenceGroup = "Sequences and dynamic scenes";
constexpr const char* kSeedGroup = "Seed-specific: DACRT (seed 001) and cones (seed 000)";
constexpr const char* kRunGroup = "Run control";

// One line per flag: the value's kind and default, without CLI11's range
// text ("INT:INT in [1 - 64]"), which pushed every description onto a line
// of its own; the ranges that matter are in the descriptions, and a value
// outside one is still a one-line error naming it. Sets ({a,b}) stay.
class CompactFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    if (opt->get_type_size() == 0) return {};  // a flag
    const std::string full = opt->get_type_name();
    std::string kind = full.substr(0, full.find(':'));
    for (size_t at = full.find(":{"); at != std::string::npos; at = full.find(":{", at + 1))
      kind = full.substr(at + 1, full.find('}', at) - at);
    std::string text = " " + kind;
    if (!opt->get_default_str().empty()) text += "=" + opt->get_default_str();
    if (opt->get_expected_max() > 1) text += " ...";
    return text;
  }
};

// "x,y,z" with three finite numbers and nothing else.
glm::vec3 parseVector(const std::string& option, const std::string& text) {
  glm::vec3 v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    auto [next, ec] = std::from_chars(p, end, v[i]);
    if (ec != std::errc() || !std::isfinite(v[i]) || (i < 2 && (next == end || *next != ',')) ||
        (i == 2 && next != end))
      throw std::runtime_error(option + ": expected x,y,z with three finite numbers, got '" + text + "'");
    p = next + 1;
  }
  return v;
}

// What the parser reads as text or checks after parsing, before it goes into Options.
struct Raw {
  int size = 0;
  std::string eye, lookAt, up;
  std::vector<std::string> lights;
  float fov = 0.0f;
  float aoDistance = 0.0f;
};

void addSceneOptions(CLI::App& app, Options& o, Raw& raw) {
  app.add_option("-s,--scene", o.scene,
                 "0 cows, 1 robots, 2 kitchen, 3 bunny, 4 cornell (thesis order), by number or name; spheres "
                 "(procedural); conference, sibenik, sponza, teapot, dragon (--scenes-dir); or a .obj .aff .nff .gltf .glb .ply .stl .off .dae .3ds .x .fbx file")
      ->capture_default_str()->group(kSceneGroup);
  app.add_option("--triangles", o.triangles, "size of the procedural 'spheres' scene (at least this many triangles)")
      ->check(CLI::Range(kSphereFieldMinTriangles, kSphereFieldMaxTriangles))->capture_default_str()
      ->group(kSceneGroup);
  app.add_option("--bart-dir", o.bartDir,
                 "where the BART scenes kitchen/ and robots/ are (default: $PASSTRACE_BART_DIR, else "
                 "../shared/scenes/bart)")->group(kSceneGroup);
  app.add_option("--scenes-dir", o.scenesDir,
                 "where the real scenes conference, sibenik, sponza, teapot, dragon are (default: "
                 "$PASSTRACE_SCENES_DIR, else ../shared/scenes/real)")->group(kSceneGroup);
  app.add_option("--eye", raw.eye, "camera position x,y,z in the file's units (default: the scene's view)")
      ->group(kSceneGroup);
  app.add_option("--look-at", raw.lookAt, "point the camera looks at, x,y,z")->group(kSceneGroup);
  app.add_option("--up", raw.up, "camera up vector x,y,z")->group(kSceneGroup);
  app.add_option("--fov", raw.fov, "vertical field of view in degrees")->check(CLI::Range(0.001f, 179.999f))
      ->group(kSceneGroup);
  app.add_option("-n,--angles", o.angles, "camera-path angles to render (thesis figure 27); 1: the scene's own view")
      ->check(CLI::Range(1, 100000))->capture_default_str()->group(kSceneGroup);
}

void addOutputOptions(CLI::App& app, Options& o, Raw& raw) {
  app.add_option("-w,--resolution", raw.size, "render N x N pixels (default 512)")->check(CLI::Range(1, kMaxImageSide))
      ->group(kOutputGroup);
  app.add_option("--width", o.width, "image width in pixels")->check(CLI::Range(1, kMaxImageSide))->group(kOutputGroup);
  app.add_option("--height", o.height, "image height in pixels")->check(CLI::Range(1, kMaxImageSide))
      ->group(kOutputGroup);
  app.add_option("-o,--output", o.output, "write the image; the format follows the extension (OpenImageIO)")
      ->group(kOutputGroup);
  app.add_flag("-p,--dump-images", o.dumpImages, "write every angle's image (NAME_k.EXT for -o NAME.EXT)")
      ->group(kOutputGroup);
  app.add_option("--hits", o.hits, "write primary-ray hit records as OpenEXR (t, u, v float; id uint32)")
      ->group(kOutputGroup);
  app.add_option("--heatmap", o.heatmap, "write per-pixel traversal steps (all bounces) as a heat map image")
      ->group(kOutputGroup);
  app.add_option("--json", o.json, "write the run's measurements as JSON (with --list: the list; no FILE: stdout)")
      ->expected(0, 1)->group(kOutputGroup);
  app.add_flag("--stats", o.stats, "print the structure's memory and the per-ray step statistics")->group(kOutputGroup);
  app.add_option("--export", o.exportPath,
                 "write the scene's triangles as passtrace built them (same order as --hits ids) to FILE.obj "
                 "(+ .mtl), .gltf or .glb, and exit")->group(kOutputGroup);
}

void addStructureOptions(CLI::App& app, Options& o) {
  app.add_option("-r,--renderer", o.renderer,
                 "0 OpenGL preview, 1 CPU ray tracer, 2 GPU stream ray tracer, 3 CPU through Embree (the baseline)")
      ->check(CLI::Range(0, 3))->capture_default_str()->group(kStructureGroup);
  app.add_option("-a,--accel", o.accelerator,
                 "structure: a name, or its thesis number (Table 4) in the renderer's column (listed below)")
      ->capture_default_str()->group(kStructureGroup);
  app.add_option("--triangle-test", o.triangleTest,
                 "ray/triangle test: moller-trumbore (the thesis's) or watertight (Woop, Benthin, Wald 2013); -r 3 "
                 "uses Embree's")
      ->check(CLI::IsMember({"moller-trumbore", "watertight"}))->capture_default_str()->group(kStructureGroup);
}

void addBuildOptions(CLI::App& app, Options& o) {
  app.add_option("-t,--gs-tries", o.gsTries, "Goldsmith/Salmon BVH constructions; the cheapest is kept")
      ->check(CLI::Range(1, 100000))->capture_default_str()->group(kBuildGroup);
  app.add_option("-c,--swap-children", o.swapChildren, "K/K BVH: children swapped with probability 0.5 c (0-2)")
      ->check(CLI::Range(0, 2))->capture_default_str()->group(kBuildGroup);
  app.add_option("-g,--grid-multiplier", o.gridMultiplier, "uniform grid resolution factor")
      ->check(CLI::Range(0.001f, 1000.0f))->capture_default_str()->group(kBuildGroup);
  app.add_option("-e,--kd-min-elements", o.kdMinElements, "kd-tree: fewest triangles for an internal node")
      ->check(CLI::Range(1, 1000000))->capture_default_str()->group(kBuildGroup);
  app.add_option("-d,--kd-max-depth", o.kdMaxDepth, "kd-tree maximum depth (0: 8 + 1.3 log2 N)")
      ->check(CLI::Range(0, 64))->capture_default_str()->group(kBuildGroup);
  app.add_option("--kd-builder", o.kdBuilder,
                 "kd-tree SAH: exact (every clipped triangle bound a candidate) or binned (up to 64 bins per axis)")
      ->check(CLI::IsMember({"exact", "binned"}))->capture_default_str()->group(kBuildGroup);
  app.add_option("--kd-termination", o.kdTermination,
                 "kd-tree leaves: thesis (-e, -d) or papay (seed 003: depth ceil(2 + 1.2 log2 N), leaves below "
                 "2/8/12 triangles)")
      ->check(CLI::IsMember({"thesis", "papay"}))->capture_default_str()->group(kBuildGroup);
  app.add_option("--stack-size", o.stackSize, "kd short-stack rows: circular stack entries (1-8; the oldest dropped)")
      ->check(CLI::Range(1, 8))->capture_default_str()->group(kBuildGroup);
  app.add_option("--bvh-builder", o.bvhBuilder,
                 "bvh-stack, bvh-octant: binned SAH, spatial-split SBVH (Stich et al. 2009) or centroid middle")
      ->check(CLI::IsMember({"sah", "sbvh", "middle"}))->capture_default_str()->group(kBuildGroup);
  app.add_option("--bvh8-builder", o.bvh8Builder,
                 "bvh8, bvh8-packet: binary tree collapsed to 8 wide, binned SAH on all cores or SBVH on one thread")
      ->check(CLI::IsMember({"binned", "sbvh"}))->capture_default_str()->group(kBuildGroup);
}

void addShadingOptions(CLI::App& app, Options& o, Raw& raw) {
  app.add_option("-b,--bounces", o.bounces, "traces per path, primary and shadow rays included; 1: primary only (1-64)")
      ->check(CLI::Range(1, 64))->capture_default_str()->group(kShadingGroup);
  app.add_option("--shading", o.shading,
                 "ray mix: thesis (diffuse, a shadow ray, mirrors), whitted (reflection, refraction, Phong) or ao "
                 "(ambient occlusion; -b not read)")
      ->check(CLI::IsMember({"thesis", "whitted", "ao"}))->capture_default_str()->group(kShadingGroup);
  app.add_option("--light", raw.lights,
                 "a point light at x,y,z in the file's units; repeat for several; replaces the file's lights "
                 "(default: the file's, else one framed on the view)")
      ->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->group(kShadingGroup);
  app.add_option("--ao-samples", o.aoSamples, "--shading ao: cosine-distributed rays per primary hit")
      ->check(CLI::Range(1, 4096))->capture_default_str()->group(kShadingGroup);
  app.add_option("--ao-distance", raw.aoDistance, "--shading ao: AO ray length (default: 0.1 x the scene's diagonal)")
      ->check(CLI::PositiveNumber)->group(kShadingGroup);
}

void addStreamOptions(CLI::App& app, Options& o) {
  app.add_option("-l,--loop-limit", o.loopLimit,
                 "traversal steps per ray per pass (the thesis: 20); 0: one pass per bounce")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str()->group(kStreamGroup);
  app.add_option("--stage", o.stage,
                 "the GL stage that runs the kernels: fragment passes (the thesis's model) or compute shaders "
                 "over lists of the active rays")
      ->check(CLI::IsMember({"fragment", "compute"}))->capture_default_str()->group(kStreamGroup);
  app.add_option("--compact", o.compact,
                 "gather live rays into whole 4x4 blocks before tracing: when at most half are live (on), always, "
                 "or off (the thesis's stream)")
      ->check(CLI::IsMember({"off", "on", "always"}))->capture_default_str()->group(kStreamGroup);
  app.add_option("--grid-kernels", o.gridKernels, "uniform grid: one merged kernel, or Purcell's split kernels")
      ->check(CLI::IsMember({"merged", "split"}))->capture_default_str()->group(kStreamGroup);
  app.add_option("--page-texels", o.pageTexels,
                 "texels per data texture (a power of two; larger data spreads over several); 0: the GL's largest")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 31))->capture_default_str()->group(kStreamGroup);
  app.add_option("--gl-backend", o.glBackend, "headless OpenGL through EGL or OSMesa (-r 0 and -r 2)")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))->capture_default_str()->group(kStreamGroup);
}

void addSequenceOptions(CLI::App& app, Options& o) {
  app.add_option("--time", o.time, "animation time: AFF keyframes (Kochanek-Bartels), glTF animations and morphs")
      ->check(CLI::Range(-1e6f, 1e6f))->capture_default_str()->group(kSequenceGroup);
  app.add_option("--frames", o.frames,
                 "render N frames over --time-start..--time-end, rebuilding each frame (-o NAME.png writes "
                 "NAME_0000.png ...)")
      ->check(CLI::Range(1, 100000))->group(kSequenceGroup);
  app.add_option("--time-start", o.timeStart, "first time of --frames (default: the animation's start)")
      ->group(kSequenceGroup);
  app.add_option("--time-end", o.timeEnd, "last time of --frames (default: the animation's end)")
      ->group(kSequenceGroup);
  app.add_option("--dynamic", o.dynamic,
                 "kd rows with --frames: rebuild one tree, two-trees (static + moving), or merge the moving tree in")
      ->check(CLI::IsMember({"rebuild", "two-trees", "merge"}))->capture_default_str()->group(kSequenceGroup);
}

void addSeedOptions(CLI::App& app, Options& o) {
  app.add_option("--dacrt-rlimit", o.dacrtRLimit, "dacrt: trace naively at this many rays or fewer in a cell")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str()->group(kSeedGroup);
  app.add_option("--dacrt-plimit", o.dacrtPLimit, "dacrt: trace naively at this many triangles or fewer in a cell")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str()->group(kSeedGroup);
  app.add_flag("--dacrt-cones", o.dacrtCones, "dacrt: conic packets, a cone per 8x8 primary (and shadow) rays")
      ->group(kSeedGroup);
  app.add_option("--dacrt-split", o.dacrtSplit, "dacrt: split at the mean of sampled midpoints (the seed's) or median")
      ->check(CLI::IsMember({"mean", "median"}))->capture_default_str()->group(kSeedGroup);
  app.add_option("--cone", o.cone,
                 "one cone per pixel instead of rays, half-angle DEG (0 <= DEG < 90); rows with a cone traversal")
      ->group(kSeedGroup);
  app.add_option("--cone-max", o.coneMax, "with --cone: keep the N nearest triangles per cone (0: every one met)")
      ->check(CLI::Range(0u, 1u << 30))->capture_default_str()->group(kSeedGroup);
  app.add_option("--cone-hits", o.coneHits,
                 "with --cone: write per pixel count, nearest id (uint32) and its axis distance t as OpenEXR")
      ->group(kSeedGroup);
  app.add_option("--cone-nodes", o.coneNodes,
                 "with --cone, kk-bvh: stack (nearer child first) or sorted (stop beyond the n-th hit)")
      ->check(CLI::IsMember({"stack", "sorted"}))->capture_default_str()->group(kSeedGroup);
  app.add_option("--cone-capacity", o.coneCapacity, "with --cone, -r 2: distinct triangles each cone's list holds")
      ->check(CLI::Range(1u, 1u << 20))->capture_default_str()->group(kSeedGroup);
}

void addRunOptions(CLI::App& app, Options& o) {
  app.add_option("-m,--repeats", o.repeats, "timed repeats of each frame; the minimum is reported")
      ->check(CLI::Range(1, 100000))->capture_default_str()->group(kRunGroup);
  app.add_option("--threads", o.threads, "CPU renderer and structure build threads (0: all cores)")
      ->check(CLI::Range(0u, kMaxThreads))->capture_default_str()->group(kRunGroup);
  app.add_flag("-q,--quiet", o.quiet, "print nothing but errors")->group(kRunGroup);
  app.add_flag("--progress", o.progress, "show loading, building and frame progress on stderr (default: on a terminal)")
      ->group(kRunGroup);
  app.add_flag("--list", o.list, "list the renderers, structures and scenes (with --json: as JSON) and exit")
      ->group(kRunGroup);
  app.add_flag("--version", o.version, "print the version and exit")->group(kRunGroup);
  app.set_help_flag("-h,--help", "print this help and exit")->group(kRunGroup);
}

}  // namespace

int parseOptions(int argc, char** argv, Options& o, std::string_view helpFooter) {
  CLI::App app{"passtrace: ray tracing acceleration structures as OpenGL stream kernels and on the CPU"};
  app.formatter(std::make_shared<CompactFormatter>());
  app.get_formatter()->column_width(34);
  app.set_help_flag();  // re-added last, under "Run control"
  Raw raw;
  addSceneOptions(app, o, raw);
  addOutputOptions(app, o, raw);
  addStructureOptions(app, o);
  addBuildOptions(app, o);
  addShadingOptions(app, o, raw);
  addStreamOptions(app, o);
  addSequenceOptions(app, o);
  addSeedOptions(app, o);
  addRunOptions(app, o);
  if (!helpFooter.empty()) app.footer(std::string(helpFooter));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return -1;
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    for (char& c : message)
      if (c == '\n') c = ' ';
    throw std::runtime_error(message);
  }
  // CLI::Range lets NaN through: every comparison with it is false.
  for (const auto& [name, value] : {std::pair{"--time", o.time}, {"--grid-multiplier", o.gridMultiplier}, {"--fov", raw.fov}})
    if (std::isnan(value)) throw std::runtime_error(std::string(name) + ": not a number");
  if (raw.size > 0) {
    if (app.count("--width") || app.count("--height"))
      throw std::runtime_error("-w sets both sides; do not combine it with --width or --height");
    o.width = o.height = raw.size;
  }
  if (!raw.eye.empty()) o.eye = parseVector("--eye", raw.eye);
  if (!raw.lookAt.empty()) o.lookAt = parseVector("--look-at", raw.lookAt);
  if (!raw.up.empty()) o.up = parseVector("--up", raw.up);
  for (const std::string& light : raw.lights) o.lights.push_back(parseVector("--light", light));
  if (app.count("--fov")) o.fov = raw.fov;
  if (app.count("--ao-distance")) {
    if (!std::isfinite(raw.aoDistance)) throw std::runtime_error("--ao-distance: not a finite positive length");
    o.aoDistance = raw.aoDistance;
  }
  o.coneMaxGiven = app.count("--cone-max") > 0;
  if (app.count("--cone-nodes") && !o.cone) throw std::runtime_error("--cone-nodes needs --cone");
  if (app.count("--cone-capacity") && !o.cone) throw std::runtime_error("--cone-capacity needs --cone");
  if (o.quiet && o.progress) throw std::runtime_error("--quiet and --progress contradict each other");
  if (app.count("--json") && o.json.empty() && !o.list) throw std::runtime_error("--json: needs a file name");
  o.listJson = o.list && app.count("--json") > 0;
  o.accelGiven = app.count("--accel") > 0;
  for (const char* flag : {"--swap-children", "--gs-tries", "--grid-multiplier", "--kd-min-elements", "--kd-max-depth",
                           "--grid-kernels", "--loop-limit", "--page-texels", "--triangle-test", "--stack-size",
                           "--kd-builder", "--kd-termination", "--dynamic",
                           "--dacrt-rlimit", "--dacrt-plimit", "--dacrt-cones", "--dacrt-split",
                           "--bvh-builder",
                           "--bvh8-builder"})
    if (app.count(flag)) o.givenFlags.emplace_back(flag);
  return 0;
}

}  // namespace passtrace
