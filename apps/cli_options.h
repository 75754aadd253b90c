#pragma once
// tracy's command line (thesis Appendix A) with descriptive long names, plus
// passtrace's outputs and camera controls.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/sphere_field.h"

namespace passtrace {

// The command line accepts up to this many pixels on a side; the GPU
// renderers are further held to the GL's texture limit and the CPU renderer
// to kMaxCpuPixels.
inline constexpr int kMaxImageSide = 65536;
inline constexpr long long kMaxCpuPixels = 16384LL * 16384LL;  // about 20 GiB of path state
// --threads: far beyond any core count, yet no run can ask for billions of threads.
inline constexpr unsigned kMaxThreads = 1024;

struct Options {
  int renderer = 2;                 // -r: 0 OpenGL preview, 1 CPU, 2 GPU stream, 3 CPU through Embree
  std::string accelerator = "0";    // -a: number (thesis Table 4) or name
  std::string scene = "bunny";      // -s: name or file
  uint64_t triangles = kSphereFieldDefaultTriangles;  // --triangles: size of the "spheres" scene
  std::string bartDir;              // --bart-dir: where kitchen/ and robots/ are (else $PASSTRACE_BART_DIR)
  std::string scenesDir;            // --scenes-dir: where the real scenes are (else $PASSTRACE_SCENES_DIR)
  float time = 0.0f;                // --time: AFF animation time
  int width = 512, height = 512;    // -w N, or --width/--height
  int bounces = 3;                  // -b: traces per path, primary and shadow rays included
  bool dumpImages = false;          // -p: write every rendered image
  int gsTries = 10;                 // -t: Goldsmith/Salmon constructions to keep the best of
  float gridMultiplier = 1.0f;      // -g: uniform grid resolution factor
  int kdMinElements = 2;            // -e: kd-tree: fewest triangles for an internal node
  int kdMaxDepth = 0;               // -d: kd-tree maximum depth, 0 = 8 + 1.3 log2 N
  int repeats = 1;                  // -m: timed repeats, the minimum is reported
  int angles = 1;                   // -n: camera-path angles
  int loopLimit = 0;                // -l: GPU traversal steps per pass, 0 = one pass per bounce
  int stackSize = 4;                // --stack-size: kd short-stack entries, 1-8
  int swapChildren = 1;             // -c: K/K child swap probability = 0.5 c
  unsigned threads = 0;             // --threads: CPU renderer threads, 0 = all cores
  std::optional<glm::vec3> eye, lookAt, up;
  std::optional<float> fov;
  std::vector<glm::vec3> lights;    // --light x,y,z (repeatable): replace the file's lights
  std::string output;               // -o
  std::string hits;                 // --hits (OpenEXR)
  std::string json;                 // --json FILE (with --list and no FILE: standard output)
  std::string glBackend = "auto";   // --gl-backend
  std::string gridKernels = "merged";  // --grid-kernels: merged or split (Purcell)
  std::string stage = "fragment";      // --stage: fragment or compute (-r 2)
  std::string compact = "off";         // --compact: off, on or always (live-ray compaction, -r 2)
  std::string triangleTest = "moller-trumbore";  // --triangle-test: moller-trumbore or watertight
  std::string kdBuilder = "exact";      // --kd-builder: exact or binned SAH
  std::string kdTermination = "thesis";  // --kd-termination: thesis (-e/-d) or papay (seed 003)
  uint64_t pageTexels = 0;          // --page-texels: GPU data texture size, 0 = the GL's largest
  int dacrtRLimit = 20;             // --dacrt-rlimit: DACRT traces naively at this many rays or fewer
  int dacrtPLimit = 16;             // --dacrt-plimit: ... or this many triangles or fewer
  bool dacrtCones = false;          // --dacrt-cones: DACRT's conic packets
  std::string dacrtSplit = "mean";  // --dacrt-split: mean (the seed's) or median
  std::string bvhBuilder = "sah";   // --bvh-builder: the stack BVH's sah, sbvh or middle builder
  std::string bvh8Builder = "binned";  // --bvh8-builder: bvh8's binary tree, binned or sbvh
  std::string heatmap;              // --heatmap: per-pixel traversal steps as an image
  std::string exportPath;           // --export: write the scene's triangles (.obj/.gltf/.glb) and exit
  int frames = 0;                   // --frames N: render a sequence over the animation (0: one frame at --time)
  std::optional<float> timeStart, timeEnd;  // --time-start/--time-end (default: the scene's animation range)
  std::string dynamic = "rebuild";  // --dynamic: rebuild, two-trees or merge (with --frames, kd rows)
  std::string shading = "thesis";   // --shading: thesis, whitted or ao
  int aoSamples = 16;               // --ao-samples: AO rays per primary hit
  float aoDistance = 0.0f;          // --ao-distance: AO ray length, 0 = a tenth of the scene's diagonal
  bool stats = false;               // --stats: print structure and per-ray statistics
  bool quiet = false;               // -q: print nothing but errors
  bool progress = false;            // --progress: stages on stderr even when it is no terminal
  bool list = false;                // --list: renderers, structures and scenes
  bool listJson = false;            // --list --json: the same as JSON
  bool version = false;             // --version
  bool accelGiven = false;          // -a was given
  // The build and traversal flags given, by long name ("--grid-multiplier"):
  // the run warns of those the chosen structure does not read.
  std::vector<std::string> givenFlags;
  std::optional<float> cone;        // --cone DEG: one cone per pixel of this half-angle (accel/cone/)
  uint32_t coneMax = 0;             // --cone-max N: nearest triangles kept per cone; 0 = all
  std::string coneHits;             // --cone-hits FILE.exr: count, id (uint32), t (float)
  bool coneMaxGiven = false;
  std::string coneNodes = "stack";  // --cone-nodes: the BVH's stack or node-sorted cone traversal
  uint32_t coneCapacity = 1024;     // --cone-capacity N: -r 2's list of distinct triangles per cone
};

// Parses argv. Returns 0 with `options` filled, -1 when --help was printed
// (exit 0), or throws std::runtime_error with a one-line message.
// `helpFooter` ends --help (the structures and scenes, from the registries).
int parseOptions(int argc, char** argv, Options& options, std::string_view helpFooter = {});

}  // namespace passtrace
