// --shading, --ao-samples and --ao-distance on the command line: both
// renderers render each mode, the JSON names it, bad values are one-line
// errors with no output, and the default is the thesis rules.

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::RunResult;
using test::slurp;
using ShadingCli = test::CliTest;

TEST_F(ShadingCli, EveryModeRendersOnBothRenderersAndTheJsonNamesIt) {
  for (const char* mode : {"thesis", "whitted", "ao"})
    for (const char* renderer : {"1", "2"}) {
      const std::string name = std::string(mode) + renderer;
      const RunResult r = run(std::string("-s cornell -w 16 -a kd-restart --ao-samples 4 -r ") + renderer +
                              " --shading " + mode + " -o " + path(name + ".png") + " --json " + path(name + ".json"));
      ASSERT_EQ(r.status, 0) << name << ": " << r.err;
      const auto j = nlohmann::json::parse(slurp(path(name + ".json")));
      EXPECT_EQ(j["shading"], mode);
      EXPECT_TRUE(fs::exists(path(name + ".png")));
    }
  // The default is the thesis rules: the same image as without the flag.
  ASSERT_EQ(run("-s cornell -w 16 -a kd-restart -r 1 -o " + path("default.png")).status, 0);
  EXPECT_EQ(slurp(path("default.png")), slurp(path("thesis1.png")));
  EXPECT_NE(slurp(path("ao1.png")), slurp(path("thesis1.png")));
}

TEST_F(ShadingCli, BadValuesAreOneLineErrorsWithNoOutput) {
  const std::string outs = " -s cornell -w 8 -o " + path("x.png") + " --json " + path("x.json");
  expectOneLineError(run("--shading phong" + outs), "--shading");
  expectOneLineError(run("--shading" + outs), "--shading");
  for (const char* samples : {"0", "-3", "4097", "many", "1.5"})
    expectOneLineError(run(std::string("--shading ao --ao-samples ") + samples + outs), "--ao-samples");
  for (const char* distance : {"0", "-1", "nan", "inf", "far"})
    expectOneLineError(run(std::string("--shading ao --ao-distance ") + distance + outs), "--ao-distance");
}

}  // namespace
}  // namespace passtrace
