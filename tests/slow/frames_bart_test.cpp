// --frames 30 over BART Robots (its `a 0 50 800` line is the range): 30
// distinct images, each frame's structure rebuilt (build and trace times in
// the JSON), the robots marked moving and the city static. Skipped without
// ../shared.

#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/bart_dir.h"
#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::slurp;
using Cli = test::CliTest;

TEST_F(Cli, FramesOverBartRobots) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "robots")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  const auto r = run("-s robots --bart-dir " + bart.string() + " -r 1 -w 24 -b 1 --frames 30 -o " + path("r.png") +
                     " --json " + path("r.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> images;
  for (int k = 0; k < 30; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "r_%04d.png", k);
    images.insert(slurp(path(name)));
  }
  EXPECT_EQ(images.size(), 30u);
  const nlohmann::json j = nlohmann::json::parse(slurp(path("r.json")));
  ASSERT_EQ(j["sequence"].size(), 30u);
  EXPECT_FLOAT_EQ(j["sequence"][29]["time"].get<float>(), 50.0f);
  for (const auto& f : j["sequence"]) {
    EXPECT_GT(f["build_ms"].get<double>(), 0.0);
    EXPECT_GT(f["moving_triangles"].get<size_t>(), 0u);
    EXPECT_LT(f["moving_triangles"].get<size_t>(), f["triangles"].get<size_t>());
  }
}

}  // namespace
}  // namespace passtrace
