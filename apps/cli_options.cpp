#include "apps/cli_options.h"

#include <charconv>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <utility>

#include <CLI/CLI.hpp>

namespace passtrace {
namespace {

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

}  // namespace

int parseOptions(int argc, char** argv, Options& o, std::string_view helpFooter) {
  CLI::App app{"passtrace: ray tracing acceleration structures as OpenGL stream kernels and on the CPU"};
  app.get_formatter()->column_width(34);
  int size = 0;
  std::string eye, lookAt, up;
  float fov = 0.0f;
  float aoDistance = 0.0f;
  app.add_option("-r,--renderer", o.renderer,
                 "0 OpenGL rasterized preview, 1 CPU ray tracer, 2 GPU stream ray tracer, 3 CPU ray tracer through "
                 "Intel Embree (the baseline; -a is not read)")
      ->check(CLI::Range(0, 3))->capture_default_str();
  app.add_option("-a,--accel", o.accelerator,
                 "acceleration structure: a name, or its thesis number (Table 4) in the renderer's column; "
                 "the structures are listed below and by --list")
      ->capture_default_str();
  app.add_option("-s,--scene", o.scene,
                 "scene: 0 cows, 1 robots, 2 kitchen, 3 bunny, 4 cornell (thesis order), by number or name; "
                 "spheres (procedural, --triangles); or a .obj, .aff, .nff, .gltf, .glb, .ply, .stl, .off, .dae, .3ds, .x or .fbx file")
      ->capture_default_str();
  app.add_option("--triangles", o.triangles, "size of the procedural 'spheres' scene (at least this many triangles)")
      ->check(CLI::Range(kSphereFieldMinTriangles, kSphereFieldMaxTriangles))->capture_default_str();
  app.add_option("--bart-dir", o.bartDir,
                 "directory holding the BART scenes kitchen/ and robots/ (default: $PASSTRACE_BART_DIR, else "
                 "../shared/scenes/bart)");
  app.add_option("--time", o.time, "animation time: AFF keyframes (Kochanek-Bartels), glTF animations and morph weights")
      ->check(CLI::Range(-1e6f, 1e6f))->capture_default_str();
  app.add_option("-w,--resolution", size, "render N x N pixels (default 512)")->check(CLI::Range(1, kMaxImageSide));
  app.add_option("--width", o.width, "image width in pixels")->check(CLI::Range(1, kMaxImageSide));
  app.add_option("--height", o.height, "image height in pixels")->check(CLI::Range(1, kMaxImageSide));
  app.add_option("-b,--bounces", o.bounces, "traces per path, primary and shadow rays included; 1 = primary only")
      ->check(CLI::Range(1, 64))->capture_default_str();
  app.add_flag("-p,--dump-images", o.dumpImages, "write every rendered image (NAME_k.EXT for -o NAME.EXT)");
  app.add_option("-t,--gs-tries", o.gsTries, "Goldsmith/Salmon BVH constructions, the cheapest is kept")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  app.add_option("-g,--grid-multiplier", o.gridMultiplier, "uniform grid resolution factor")
      ->check(CLI::Range(0.001f, 1000.0f))->capture_default_str();
  app.add_option("-e,--kd-min-elements", o.kdMinElements, "kd-tree: fewest triangles for an internal node")
      ->check(CLI::Range(1, 1000000))->capture_default_str();
  app.add_option("-d,--kd-max-depth", o.kdMaxDepth, "kd-tree maximum depth (0: 8 + 1.3 log2 N)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("-m,--repeats", o.repeats, "timed repeats of each frame; the minimum is reported")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  app.add_option("-n,--angles", o.angles,
                 "camera-path angles to render (thesis figure 27); 1 renders the scene's own view")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("-l,--loop-limit", o.loopLimit,
                 "GPU traversal steps per ray per pass (the thesis: 20); 0 = one pass per bounce. On llvmpipe a "
                 "pass runs at most what its shader loop cap allows")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  app.add_option("--stack-size", o.stackSize,
                 "kd-shortstack, kd-pushdown-shortstack: entries of the circular stack (the oldest is dropped "
                 "when full)")
      ->check(CLI::Range(1, 8))->capture_default_str();
  app.add_option("-c,--swap-children", o.swapChildren, "K/K BVH: children swapped with probability 0.5 c")
      ->check(CLI::Range(0, 2))->capture_default_str();
  app.add_option("--threads", o.threads, "CPU renderer and structure build threads (0: all cores)")
      ->check(CLI::Range(0u, kMaxThreads))->capture_default_str();
  app.add_option("--eye", eye, "camera position x,y,z (default: the scene's view)");
  app.add_option("--look-at", lookAt, "point the camera looks at x,y,z");
  app.add_option("--up", up, "camera up vector x,y,z");
  app.add_option("--fov", fov, "vertical field of view in degrees")->check(CLI::Range(0.001f, 179.999f));
  app.add_option("-o,--output", o.output, "write the image; the format follows the extension (OpenImageIO)");
  app.add_option("--hits", o.hits, "write primary-ray hit records as OpenEXR (t, u, v float; id uint32)");
  app.add_option("--json", o.json, "write the run's measurements as JSON (with --list: the list, to standard output "
                 "when no FILE is given)")->expected(0, 1);
  app.add_option("--gl-backend", o.glBackend, "auto, egl or osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))->capture_default_str();
  app.add_option("--grid-kernels", o.gridKernels,
                 "GPU uniform grid: merged traversal+intersection kernel, or Purcell's split kernels")
      ->check(CLI::IsMember({"merged", "split"}))->capture_default_str();
  app.add_option("--triangle-test", o.triangleTest,
                 "ray/triangle test of the CPU and GPU ray tracers: moller-trumbore (the thesis's) or watertight "
                 "(Woop, Benthin, Wald 2013: no ray slips between triangles sharing an edge); -r 3 uses "
                 "Embree's own test and ignores it")
      ->check(CLI::IsMember({"moller-trumbore", "watertight"}))->capture_default_str();
  app.add_option("--kd-builder", o.kdBuilder,
                 "kd-tree SAH build: exact (every clipped triangle bound a candidate plane) or binned (min-max "
                 "binning, up to 64 bins per axis)")
      ->check(CLI::IsMember({"exact", "binned"}))->capture_default_str();
  app.add_option("--kd-termination", o.kdTermination,
                 "kd-tree leaves: thesis (-e, -d) or papay (seed 003: depth ceil(2 + 1.2 log2 N), leaf below 2/8/12 "
                 "triangles for N < 700K / <= 3M / more; replaces -e and -d)")
      ->check(CLI::IsMember({"thesis", "papay"}))->capture_default_str();
  app.add_option("--page-texels", o.pageTexels,
                 "GPU: texels per data texture (rounded down to a power of two); larger data spreads over "
                 "several textures. 0: the largest texture the GL accepts")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 31))->capture_default_str();
  app.add_option("--dacrt-rlimit", o.dacrtRLimit, "dacrt: trace naively when this many rays or fewer remain in a cell")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  app.add_option("--dacrt-plimit", o.dacrtPLimit,
                 "dacrt: trace naively when this many triangles or fewer remain in a cell")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  app.add_flag("--dacrt-cones", o.dacrtCones,
               "dacrt: conic packets, a cone per 8x8 primary rays (and per 8x8 pixels' shadow rays, from the light)");
  app.add_option("--dacrt-split", o.dacrtSplit,
                 "dacrt: split position, mean (of sampled triangle midpoints above 10,000 triangles, the seed's) "
                 "or median (always the middle of the cell)")
      ->check(CLI::IsMember({"mean", "median"}))->capture_default_str();
  app.add_option("--bvh-builder", o.bvhBuilder,
                 "bvh-stack, bvh-octant: binned SAH (sah), split BVH with spatial splits (sbvh, Stich et al. 2009) "
                 "or the middle of the centroid box's largest axis (middle)")
      ->check(CLI::IsMember({"sah", "sbvh", "middle"}))->capture_default_str();
  app.add_option("--bvh8-builder", o.bvh8Builder,
                 "bvh8, bvh8-packet: the binary tree collapsed to 8 wide, binned SAH on all cores (binned) or split "
                 "BVH with spatial splits on one thread (sbvh, Stich et al. 2009; references <= 2x triangles)")
      ->check(CLI::IsMember({"binned", "sbvh"}))->capture_default_str();
  app.add_option("--heatmap", o.heatmap, "write per-pixel traversal steps (all bounces) as a heat map image");
  app.add_flag("--stats", o.stats, "print the structure's memory and the per-ray step statistics");
  app.add_flag("-q,--quiet", o.quiet, "print nothing but errors");
  app.add_flag("--progress", o.progress, "show loading, building and frame progress on stderr (default: when it is a "
               "terminal)");
  app.add_option("--frames", o.frames,
                 "render N frames evenly over --time-start..--time-end (default: the scene's animation range), "
                 "rebuilding the structure each frame (see --dynamic): -o NAME.png writes NAME_0000.png ... (default "
                 "frame_0000.png), --hits NAME.exr NAME_0000.exr ...; --json reports each frame's build and trace times")
      ->check(CLI::Range(1, 100000));
  app.add_option("--dynamic", o.dynamic,
                 "with --frames, kd rows: rebuild one tree each frame; two-trees: a static tree built once and a "
                 "tree over the moving triangles each frame, both traced; merge: the moving triangles' tree merged "
                 "into the static tree each frame")
      ->check(CLI::IsMember({"rebuild", "two-trees", "merge"}))->capture_default_str();
  app.add_option("--time-start", o.timeStart, "first time of --frames (default: the animation's start)");
  app.add_option("--time-end", o.timeEnd, "last time of --frames (default: the animation's end)");
  app.add_option("--export", o.exportPath,
                 "write the scene's triangles as passtrace built them (at --time; same order as --hits ids) to "
                 "FILE.obj (+ .mtl), .gltf or .glb, and exit without rendering");
  app.add_option("--shading", o.shading,
                 "ray mix: thesis (diffuse, one shadow ray, mirrors; -b traces per path), whitted (reflection and "
                 "refraction with Fresnel, shadow rays, Phong highlights; -b = depth of the ray tree) or ao "
                 "(ambient occlusion, grey; -b not read)")
      ->check(CLI::IsMember({"thesis", "whitted", "ao"}))->capture_default_str();
  app.add_option("--ao-samples", o.aoSamples, "--shading ao: cosine-distributed rays per primary hit")
      ->check(CLI::Range(1, 4096))->capture_default_str();
  app.add_option("--ao-distance", aoDistance,
                 "--shading ao: the AO rays' length in scene units (default: 0.1 x the scene's box diagonal)")
      ->check(CLI::PositiveNumber);
  app.add_option("--cone", o.cone,
                 "trace one cone per pixel instead of rays: axis through the pixel centre, half-angle DEG degrees "
                 "(0 <= DEG < 90); structures with a cone traversal only");
  app.add_option("--cone-max", o.coneMax, "with --cone: keep the N nearest triangles per cone (0: every one met)")
      ->check(CLI::Range(0u, 1u << 30))->capture_default_str();
  app.add_option("--cone-hits", o.coneHits,
                 "with --cone: write per pixel count (uint32: distinct triangles met, capped by --cone-max), id "
                 "(uint32: the nearest one's index, 4294967295 for none) and t (float: its axis distance) as OpenEXR");
  app.add_option("--cone-nodes", o.coneNodes,
                 "with --cone, kk-bvh: stack (nearer child first) or sorted (nodes by nearest axis distance, stop "
                 "at the first beyond the n-th hit)")
      ->check(CLI::IsMember({"stack", "sorted"}))->capture_default_str();
  app.add_option("--cone-capacity", o.coneCapacity,
                 "with --cone, -r 2: distinct triangles each cone's list holds (more with --cone-max 0 is an error)")
      ->check(CLI::Range(1u, 1u << 20))->capture_default_str();
  app.add_option("--compact", o.compact,
                 "-r 2: gather a generation's live rays into whole 4x4 blocks before tracing them (llvmpipe culls "
                 "only whole blocks): on when at most half the rays are live, always for every generation; off keeps "
                 "the thesis's stream")
      ->check(CLI::IsMember({"off", "on", "always"}))->capture_default_str();
  app.add_flag("--list", o.list, "list the renderers, structures and scenes (with --json: as JSON) and exit");
  app.add_flag("--version", o.version, "print the version and exit");
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
  for (const auto& [name, value] : {std::pair{"--time", o.time}, {"--grid-multiplier", o.gridMultiplier}, {"--fov", fov}})
    if (std::isnan(value)) throw std::runtime_error(std::string(name) + ": not a number");
  if (size > 0) {
    if (app.count("--width") || app.count("--height"))
      throw std::runtime_error("-w sets both sides; do not combine it with --width or --height");
    o.width = o.height = size;
  }
  if (!eye.empty()) o.eye = parseVector("--eye", eye);
  if (!lookAt.empty()) o.lookAt = parseVector("--look-at", lookAt);
  if (!up.empty()) o.up = parseVector("--up", up);
  if (app.count("--fov")) o.fov = fov;
  if (app.count("--ao-distance")) {
    if (!std::isfinite(aoDistance)) throw std::runtime_error("--ao-distance: not a finite positive length");
    o.aoDistance = aoDistance;
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
