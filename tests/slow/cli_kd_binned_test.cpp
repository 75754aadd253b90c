// The binned SAH kd build (both termination rules) through the command line
// for every row that reads --kd-builder, on the CPU and GPU ray tracers: the
// hit buffers equal brute force on the Cornell box and the bunny, and on the
// BART scenes (when found) for the first such row of each ray tracer: the
// build is the same for every row, and the rows' traversals meet the BART
// scenes in cli_every_structure_test.cpp. PASSTRACE_FULL_MATRIX=1 runs every
// row there too.

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

class CliBinned : public test::CliTest {
 protected:
  // Every (renderer, kd row, termination) of `runs` on one scene.
  void expectBinnedRunsMatchBruteForce(const std::vector<std::pair<int, std::string>>& runs, const std::string& name,
                                       const SceneOptions& options);
};

void CliBinned::expectBinnedRunsMatchBruteForce(const std::vector<std::pair<int, std::string>>& runs,
                                                const std::string& name, const SceneOptions& options) {
  ASSERT_FALSE(runs.empty());
  const Scene scene = loadScene(name, options);
  const std::string bartFlag = options.bartDir.empty() ? "" : " --bart-dir " + options.bartDir.string();
  for (const auto& [renderer, accel] : runs) {
    const std::string file = path("h.exr");
    const RunResult r = run("-s " + name + bartFlag + " -b 1 -w 24 -r " + std::to_string(renderer) + " -a " + accel +
                            " --hits " + file);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("is not read by"), std::string::npos) << r.err;  // the rows read both flags
    SCOPED_TRACE(name + " -r " + std::to_string(renderer) + " -a " + accel);
    expectHitsMatchBruteForce(file, scene, 24);
  }
}

TEST_F(CliBinned, CornellAndBunnyHitBuffersEqualBruteForce) {
  for (const char* name : {"cornell", "bunny"})
    expectBinnedRunsMatchBruteForce(testing_registry::kdBinnedRuns(), name, {});
}

TEST_F(CliBinned, BartScenesHitBuffersEqualBruteForce) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "kitchen")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  auto runs = testing_registry::kdBinnedRuns();
  if (!testing_registry::fullMatrix()) runs = testing_registry::firstStructurePerRenderer(runs);
  for (const char* name : {"kitchen", "robots"}) expectBinnedRunsMatchBruteForce(runs, name, SceneOptions{bart});
}

}  // namespace
}  // namespace passtrace
