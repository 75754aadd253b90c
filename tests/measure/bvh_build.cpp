// Build speed and SAH quality of the wide BVH's binned builder against the
// exact full-sweep builder (accel/wide_bvh/binary_bvh.h):
//   build/tests/measure/measure_bvh_build SCENE [TRIANGLES] [THREADS] [REPEATS] [--no-exact]
// e.g. measure_bvh_build spheres 1000000 2 5. Prints the minimum and median of
// REPEATS binned builds (and of the collapse to 8 wide), Mtriangles/s, and both
// builders' SAH costs with their ratio. Also the build's processor time (all
// threads, std::clock): on a machine shared with other work the wall time
// includes waiting, and processor time / threads is its uncontended bound.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "scenes/scene_registry.h"

using namespace passtrace;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [TRIANGLES] [THREADS] [REPEATS] [--no-exact]\n", argv[0]);
    return 2;
  }
  SceneOptions options;
  if (argc > 2) options.triangles = std::strtoull(argv[2], nullptr, 10);
  const int threads = argc > 3 ? std::atoi(argv[3]) : 0;
  const int repeats = argc > 4 ? std::max(1, std::atoi(argv[4])) : 5;
  const bool exact = !(argc > 5 && std::strcmp(argv[5], "--no-exact") == 0);
  Scene scene;
  try {
    scene = loadScene(argv[1], options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 1;
  }
  std::vector<tbb::global_control> limit;
  if (threads > 0) limit.emplace_back(tbb::global_control::max_allowed_parallelism, size_t(threads));
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  std::vector<double> build, collapse, cpu;
  SahBinaryBvh binned;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t c0 = std::clock();
    const auto t0 = Clock::now();
    binned = buildBinnedSahBvh(scene.triangles);
    const auto t1 = Clock::now();
    cpu.push_back(1e3 * double(std::clock() - c0) / CLOCKS_PER_SEC);
    const WideBvh wide = collapseToWideBvh(binned, scene.triangles);
    const auto t2 = Clock::now();
    build.push_back(ms(t0, t1)), collapse.push_back(ms(t1, t2));
  }
  std::sort(build.begin(), build.end());
  std::sort(collapse.begin(), collapse.end());
  std::sort(cpu.begin(), cpu.end());
  const double n = double(scene.triangles.size());
  std::printf("%s: %zu triangles, threads %d: binned build min %.1f ms (%.2f Mtris/s) median %.1f ms; "
              "collapse min %.1f ms; build+collapse min %.2f Mtris/s; build processor time min %.1f ms "
              "(%.2f Mtris/s per processor-second); SAH binned %.3f\n",
              argv[1], scene.triangles.size(), threads, build[0], n / build[0] / 1e3, build[build.size() / 2],
              collapse[0], n / (build[0] + collapse[0]) / 1e3, cpu[0], n / cpu[0] / 1e3, bvhSahCost(binned));
  if (exact) {
    const auto t0 = Clock::now();
    const SahBinaryBvh reference = buildExactSahBvh(scene.triangles);
    const double exactMs = ms(t0, Clock::now());
    std::printf("exact sweep build %.1f ms; SAH exact %.3f; binned / exact = %.4f\n", exactMs,
                bvhSahCost(reference), bvhSahCost(binned) / bvhSahCost(reference));
  }
  return 0;
}
