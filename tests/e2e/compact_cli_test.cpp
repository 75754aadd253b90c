// --compact on the command line: bad values are one-line errors with no
// output; off, on and always give the same image, and the JSON says which ran.

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::RunResult;
using test::slurp;
using CompactCli = test::CliTest;

TEST_F(CompactCli, BadValuesAreOneLineErrorsWithNoOutput) {
  const std::string outs = " -r 2 -s cornell -w 8 -o " + path("x.png") + " --json " + path("x.json");
  for (const char* value : {"yes", "1", "ON", "auto", ""})
    expectOneLineError(run(std::string("--compact '") + value + "'" + outs), "--compact");
  expectOneLineError(run("--compact" + outs), "--compact");
}

TEST_F(CompactCli, OnAndOffRenderTheSameImage) {
  for (const char* value : {"off", "on", "always"}) {
    const std::string name = value;
    const RunResult r = run("-r 2 -s cornell -w 16 -a kk-bvh --shading whitted -b 3 -l 3 --compact " + name + " -o " +
                            path(name + ".png") + " --json " + path(name + ".json"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(path(name + ".json")))["compact"], name);
  }
  EXPECT_EQ(slurp(path("on.png")), slurp(path("off.png")));
  EXPECT_EQ(slurp(path("always.png")), slurp(path("off.png")));
}

}  // namespace
}  // namespace passtrace
