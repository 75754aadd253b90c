// --stage on the command line (issue 38): the JSON says which stage ran
// ("fragment" by default, null off the stream renderer), both stages write
// the same image and hit buffer, and bad values or another renderer are
// one-line errors with no output.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace passtrace {
namespace {

using test::RunResult;
using test::slurp;
using StageCli = test::CliTest;

TEST_F(StageCli, TheJsonSaysTheStageAndBothStagesWriteTheSameFiles) {
  for (const std::string stage : {"", "fragment", "compute"}) {
    const std::string name = stage.empty() ? "default" : stage;
    const RunResult r = run("-r 2 -s cornell -w 24 -a bvh-octant -b 3" + (stage.empty() ? "" : " --stage " + stage) +
                            " -o " + path(name + ".exr") + " --hits " + path(name + "_hits.exr") + " --json " +
                            path(name + ".json"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(path(name + ".json")))["stage"], stage.empty() ? "fragment" : stage);
  }
  EXPECT_EQ(slurp(path("compute.exr")), slurp(path("fragment.exr")));
  EXPECT_EQ(slurp(path("compute_hits.exr")), slurp(path("fragment_hits.exr")));
  EXPECT_EQ(slurp(path("default.exr")), slurp(path("fragment.exr")));

  const RunResult cpu = run("-r 1 -s cornell -w 8 --json " + path("cpu.json"));
  ASSERT_EQ(cpu.status, 0) << cpu.err;
  EXPECT_TRUE(nlohmann::json::parse(slurp(path("cpu.json")))["stage"].is_null());
}

TEST_F(StageCli, BadValuesAndOtherRenderersAreOneLineErrorsWithNoOutput) {
  const std::string outs = " -s cornell -w 8 -o " + path("x.png") + " --json " + path("x.json");
  for (const char* value : {"vertex", "Compute", "1", ""})
    expectOneLineError(run(std::string("-r 2 --stage '") + value + "'" + outs), "--stage");
  expectOneLineError(run("-r 2 --stage" + outs), "--stage");
  for (const char* renderer : {"0", "1"})
    expectOneLineError(run(std::string("-r ") + renderer + " --stage compute" + outs), "--stage compute");
}

}  // namespace
}  // namespace passtrace
