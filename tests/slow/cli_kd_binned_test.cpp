// The binned SAH kd build (both termination rules) through the command line
// for every row that reads --kd-builder, on the CPU and GPU ray tracers: the
// hit buffers equal brute force on the Cornell box, the bunny and the BART
// scenes (when found).

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
  // Every (renderer, kd row, termination) of kdBinnedRuns on one scene.
  void expectBinnedRunsMatchBruteForce(const std::string& name, const SceneOptions& options);
};

void CliBinned::expectBinnedRunsMatchBruteForce(const std::string& name, const SceneOptions& options) {
  const auto runs = testing_registry::kdBinnedRuns();
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
  for (const char* name : {"cornell", "bunny"}) expectBinnedRunsMatchBruteForce(name, {});
}

TEST_F(CliBinned, BartScenesHitBuffersEqualBruteForce) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "kitchen")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  for (const char* name : {"kitchen", "robots"}) expectBinnedRunsMatchBruteForce(name, SceneOptions{bart});
}

}  // namespace
}  // namespace passtrace
