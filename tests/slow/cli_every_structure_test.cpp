// Every structure of the registry on every ray tracer through the command
// line: the hit buffers equal brute force on the Cornell box and the bunny,
// and on the BART scenes when they are found; the short stacks with 1, 4 and 8
// entries, bvh-stack with each --bvh-builder, the GPU kd and stack-BVH rows at
// loop limits 3 and 64.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/scene_registry.h"
#include "tests/bart_dir.h"
#include "tests/cli_support.h"
#include "tests/registry_helpers.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::expectHitsMatchBruteForce;
using test::RunResult;

// One test per (ray tracer, structure and its variant flags), so that each
// has its own time limit and ctest runs them side by side.
class EveryStructure : public test::CliTest, public ::testing::WithParamInterface<std::pair<int, std::string>> {
protected:
  // Runs the entry at each of its loop limits on `name` and checks every hit buffer.
  void checkScene(const std::string& name, const Scene& scene, const std::string& sceneArgs, int width, int threads) {
    const auto& [renderer, accel] = GetParam();
    for (const std::string& loop : testing_registry::loopLimitFlags(GetParam())) {
      const std::string file = path("h.exr");
      const RunResult r = run("-s " + name + sceneArgs + " -b 1 -w " + std::to_string(width) + " -t " +
                              std::to_string(threads) + " -r " + std::to_string(renderer) + " -a " + accel + loop +
                              " --hits " + file);
      ASSERT_EQ(r.status, 0) << r.err;
      SCOPED_TRACE(name + " -r " + std::to_string(renderer) + " -a " + accel + loop);
      expectHitsMatchBruteForce(file, scene, width);
    }
  }
};

// Issue 3: every structure on both ray tracers, bunny and Cornell box.
TEST_P(EveryStructure, HitBuffersEqualBruteForceOnCornellAndBunny) {
  for (const std::string name : {"cornell", "bunny"}) checkScene(name, loadScene(name), "", 40, 2);
}

// Issue 4: the BART scenes (skipped without ../shared); one row per family
// and renderer unless PASSTRACE_FULL_MATRIX=1.
TEST_P(EveryStructure, HitBuffersEqualBruteForceOnBartScenes) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "kitchen")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  if (!testing_registry::fullMatrix() && !testing_registry::representsItsFamily(GetParam()))
    GTEST_SKIP() << "one row per family on the BART scenes; PASSTRACE_FULL_MATRIX=1 runs every row";
  for (const std::string name : {"robots", "kitchen"})
    checkScene(name, loadScene(name, SceneOptions{bart}), " --bart-dir " + bart.string(), 24, 1);
}

INSTANTIATE_TEST_SUITE_P(Cli, EveryStructure, ::testing::ValuesIn(testing_registry::everyStructureRun()),
                         [](const auto& info) { return testing_registry::runName(info.param); });

}  // namespace
}  // namespace passtrace
