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
using Cli = test::CliTest;

// Issue 3: every structure on both ray tracers, bunny and Cornell box.
TEST_F(Cli, HitBuffersOfEveryAcceleratorEqualBruteForce) {
  const std::vector<std::pair<int, std::string>> runs = testing_registry::everyStructureRun();
  for (const char* name : {"cornell", "bunny"}) {
    const Scene scene = loadScene(name);
    for (const auto& entry : runs)
      for (const std::string& loop : testing_registry::loopLimitFlags(entry)) {
        const auto& [renderer, accel] = entry;
        const std::string file = path("h.exr");
        const RunResult r = run(std::string("-s ") + name + " -b 1 -w 40 -t 2 -r " + std::to_string(renderer) +
                                " -a " + accel + loop + " --hits " + file);
        ASSERT_EQ(r.status, 0) << r.err;
        SCOPED_TRACE(std::string(name) + " -r " + std::to_string(renderer) + " -a " + accel + loop);
        expectHitsMatchBruteForce(file, scene, 40);
      }
  }
}

// Issue 4: the BART scenes through every structure (skipped without ../shared).
TEST_F(Cli, BartScenesHitBuffersEqualBruteForceWithEveryStructure) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "kitchen")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  const std::vector<std::pair<int, std::string>> runs = testing_registry::everyStructureRun();
  for (const char* name : {"robots", "kitchen"}) {
    const Scene scene = loadScene(name, SceneOptions{bart});
    for (const auto& entry : runs)
      for (const std::string& loop : testing_registry::loopLimitFlags(entry)) {
        const auto& [renderer, accel] = entry;
        const std::string file = path("h.exr");
        const RunResult r = run(std::string("-s ") + name + " --bart-dir " + bart.string() + " -b 1 -w 24 -t 1 -r " +
                                std::to_string(renderer) + " -a " + accel + loop + " --hits " + file);
        ASSERT_EQ(r.status, 0) << r.err;
        SCOPED_TRACE(std::string(name) + " -r " + std::to_string(renderer) + " -a " + accel + loop);
        expectHitsMatchBruteForce(file, scene, 24);
      }
  }
}

}  // namespace
}  // namespace passtrace
