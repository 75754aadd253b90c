// PLY scenes (read through Assimp) on the command line: hit buffers against
// brute force, and a bad file's one-line error with no output left behind.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scenes/scene_registry.h"
#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

using test::RunResult;
using PlyCli = test::CliTest;

const fs::path kPlyData = fs::path(PASSTRACE_TEST_DATA) / "ply";

TEST_F(PlyCli, HitBuffersOfAsciiAndBinaryPlyEqualBruteForce) {
  for (const char* name : {"cube.ply", "pyramid_binary.ply"}) {
    SCOPED_TRACE(name);
    const std::string scene = (kPlyData / name).string();
    const std::string hits = path("h.exr");
    const RunResult r = run("-s " + scene + " -r 1 -w 32 --hits " + hits);
    ASSERT_EQ(r.status, 0) << r.err;
    test::expectHitsMatchBruteForce(hits, loadScene(scene), 32);
  }
}

TEST_F(PlyCli, BadPlyGivesOneLineErrorAndNoOutput) {
  const std::string outs = " -r 1 -w 16 --hits " + path("h.exr") + " -o " + path("x.png") + " --json " + path("x.json");
  expectOneLineError(run("-s " + (kPlyData / "count_too_large.ply").string() + outs), "count_too_large.ply:4");
  expectOneLineError(run("-s " + (kPlyData / "truncated_binary.ply").string() + outs), "truncated_binary.ply");
}

}  // namespace
}  // namespace passtrace
