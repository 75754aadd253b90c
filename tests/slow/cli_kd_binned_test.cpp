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
using Cli = test::CliTest;

TEST_F(Cli, BinnedKdBuildsHitBuffersEqualBruteForce) {
  const auto runs = testing_registry::kdBinnedRuns();
  ASSERT_FALSE(runs.empty());
  std::vector<std::pair<std::string, SceneOptions>> scenes = {{"cornell", {}}, {"bunny", {}}};
  const fs::path bart = test::bartDir();
  if (!bart.empty() && fs::exists(bart / "kitchen")) {
    scenes.push_back({"kitchen", SceneOptions{bart}});
    scenes.push_back({"robots", SceneOptions{bart}});
  } else {
    ADD_FAILURE() << "BART scenes not found; set PASSTRACE_BART_DIR";
  }
  for (const auto& [name, options] : scenes) {
    const Scene scene = loadScene(name, options);
    for (const auto& [renderer, accel] : runs) {
      const std::string file = path("h.exr");
      const std::string bartFlag = options.bartDir.empty() ? "" : " --bart-dir " + options.bartDir.string();
      const RunResult r = run("-s " + name + bartFlag + " -b 1 -w 24 -r " + std::to_string(renderer) + " -a " + accel +
                              " --hits " + file);
      ASSERT_EQ(r.status, 0) << r.err;
      EXPECT_EQ(r.err.find("is not read by"), std::string::npos) << r.err;  // the row reads both flags
      SCOPED_TRACE(name + " -r " + std::to_string(renderer) + " -a " + accel);
      expectHitsMatchBruteForce(file, scene, 24);
    }
  }
}

}  // namespace
}  // namespace passtrace
