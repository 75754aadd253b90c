// --dynamic rebuild|two-trees|merge through the command line on the built-in
// dynamic scene (tests/data/gltf/dynamic.gltf: static floor, pillars and
// sphere; a sphere on a rigid path, a spinning bar, a morphing sphere): 30
// frames on the CPU and the GPU stream renderer, every frame's --hits buffer
// equal to brute force on that frame's geometry, and the JSON's per-frame
// T_F; bad requests are one-line errors.

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scenes/scene_registry.h"
#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::slurp;

const std::string kScene = std::string(PASSTRACE_TEST_DATA) + "/gltf/dynamic.gltf";
constexpr int kFrames = 30, kSize = 24;

std::string numbered(const std::string& stem, int k, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%04d.%s", stem.c_str(), k, extension);
  return name;
}

struct DynamicRun {
  int renderer;
  std::string accel, strategy;
  std::string extra = "";  // more flags
};

class DynamicCli : public test::CliTest, public ::testing::WithParamInterface<DynamicRun> {};

TEST_P(DynamicCli, EveryFrameHitsEqualBruteForce) {
  const DynamicRun& p = GetParam();
  const auto r = run("-s " + kScene + " -r " + std::to_string(p.renderer) + " -a " + p.accel + " -w " +
                     std::to_string(kSize) + " -b 2 --frames " + std::to_string(kFrames) + " --dynamic " + p.strategy +
                     " -o " + path("f.png") + " --hits " + path("h.exr") + " --json " + path("f.json") + " " + p.extra);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--dynamic " + p.strategy), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("f.json")));
  EXPECT_EQ(j["dynamic"], p.strategy);
  if (p.strategy == "rebuild") EXPECT_EQ(j["static_build_ms"].get<double>(), 0.0);
  else EXPECT_GT(j["static_build_ms"].get<double>(), 0.0);
  ASSERT_EQ(j["sequence"].size(), size_t(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    const nlohmann::json& f = j["sequence"][k];
    EXPECT_GT(f["moving_triangles"].get<size_t>(), 0u);
    EXPECT_DOUBLE_EQ(f["total_ms"].get<double>(), f["build_ms"].get<double>() + f["frame_ms"].get<double>());
    ASSERT_TRUE(fs::exists(path(numbered("f", k, "png"))));
    SceneOptions options;
    options.time = f["time"].get<float>();  // the frame's own time, as the run computed it
    const Scene scene = loadScene(kScene, options);
    SCOPED_TRACE("frame " + std::to_string(k) + " at t=" + std::to_string(options.time));
    test::expectHitsMatchBruteForce(path(numbered("h", k, "exr")), scene, kSize);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, DynamicCli,
    ::testing::Values(DynamicRun{1, "kd-tree", "rebuild"}, DynamicRun{1, "kd-tree", "two-trees"}, DynamicRun{1, "kd-tree", "merge"},
                      DynamicRun{1, "kd-backtrack", "merge"}, DynamicRun{2, "kd-restart", "rebuild"},
                      DynamicRun{2, "kd-restart", "two-trees"}, DynamicRun{2, "kd-restart", "merge"},
                      DynamicRun{2, "kd-backtrack", "two-trees"}, DynamicRun{2, "kd-backtrack", "merge"},
                      // Small pages: the merged tree's page count changes between frames (kernel rebuilt).
                      DynamicRun{2, "kd-restart", "merge", "--page-texels 1024"}),
    [](const auto& info) {
      std::string name(1, 'r');
      name += char('0' + info.param.renderer);
      name.append("_").append(info.param.accel).append("_").append(info.param.strategy);
      if (!info.param.extra.empty()) name.append("_paged");
      for (char& c : name)
        if (c == '-') c = '_';
      return name;
    });

using DynamicErrors = test::CliTest;

TEST_F(DynamicErrors, AreOneLineAndLeaveNothing) {
  const std::string base = "-s " + kScene + " -w 8 -b 1 -o " + path("f.png");
  expectOneLineError(run(base + " -r 1 -a kd-tree --dynamic merge"), "--frames");
  expectOneLineError(run(base + " -r 1 -a grid --frames 3 --dynamic two-trees"), "grid");
  expectOneLineError(run(base + " -r 2 -a kk-bvh --frames 3 --dynamic rebuild"), "kk-bvh");
  expectOneLineError(run(base + " -r 0 --frames 3 --dynamic merge"), "--dynamic");
  expectOneLineError(run(base + " -r 1 -a kd-tree --frames 3 --dynamic merged"), "--dynamic");
  expectOneLineError(run(base + " -r 1 -a kd-tree --frames 3 --dynamic merge --hits " + path("h.png")), ".exr");
}

}  // namespace
}  // namespace passtrace
