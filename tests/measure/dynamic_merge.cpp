// The parts of --dynamic merge's per-frame build_ms, measured apart: the
// dynamic tree's build and the merge (kd_merge.h), with the trees' sizes.
//   build/tests/measure/measure_dynamic_merge SCENE [FRAMES] [BART_DIR]
// e.g. measure_dynamic_merge robots 30 ../shared/scenes/bart. Prints one line
// of means over FRAMES frames spread over the scene's animation.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "accel/kd/kd_dynamic.h"
#include "accel/kd/kd_merge.h"
#include "scenes/scene_registry.h"

using namespace passtrace;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [FRAMES] [BART_DIR]\n", argv[0]);
    return 2;
  }
  const int frames = argc > 2 ? std::atoi(argv[2]) : 30;
  SceneOptions options;
  if (argc > 3) options.bartDir = argv[3];
  const Scene first = loadScene(argv[1], options);
  if (!first.animation || frames < 2) {
    std::fprintf(stderr, "%s: needs an animated scene and at least 2 frames\n", argv[1]);
    return 2;
  }
  std::vector<uint32_t> staticIds, movingIds;
  for (uint32_t i = 0; i < first.triangles.size(); ++i)
    (i < first.moving.size() && first.moving[i] ? movingIds : staticIds).push_back(i);
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const auto s0 = Clock::now();
  const KdTree staticTree = buildKdTreeOver(first.triangles, staticIds, AccelBuildConfig{});
  const double staticMs = ms(s0, Clock::now());
  double build = 0, merge = 0, nodes = 0, refs = 0, dynNodes = 0;
  for (int f = 0; f < frames; ++f) {
    options.time = first.animation->start + (first.animation->end - first.animation->start) * float(f) / float(frames - 1);
    const Scene scene = loadScene(argv[1], options);
    const auto t0 = Clock::now();
    const KdTree dynamic = buildKdTreeOver(scene.triangles, movingIds, AccelBuildConfig{});
    const auto t1 = Clock::now();
    const KdTree merged = mergeKdTrees(staticTree, dynamic, scene.triangles);
    const auto t2 = Clock::now();
    build += ms(t0, t1), merge += ms(t1, t2);
    nodes += double(merged.nodes.size()), refs += double(merged.references.size());
    dynNodes += double(dynamic.nodes.size());
  }
  const double n = frames;
  std::printf("%s: %zu triangles, %zu moving; static build %.1f ms (%zu nodes); per frame: dynamic build %.2f ms "
              "(%.0f nodes), merge %.2f ms, merged tree %.0f nodes, %.0f references\n",
              first.name.c_str(), first.triangles.size(), movingIds.size(), staticMs, staticTree.nodes.size(),
              build / n, dynNodes / n, merge / n, nodes / n, refs / n);
  return 0;
}
