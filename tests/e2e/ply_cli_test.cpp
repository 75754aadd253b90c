// PLY and OFF scenes (passtrace's own readers) on the command line: hit
// buffers against brute force, and a bad file's one-line error with no output
// left behind.

#include <bit>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/ply_writer.h"

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

// Assimp 5.2 skipped a line-end byte after end_header (its issue #5341): a
// scan whose body starts with 0x0A failed, "mIndices[0] is out of range".
TEST_F(PlyCli, BinaryBodyStartingWithALineFeedTracesAsBruteForce) {
  test::PlyMesh m{{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 2}}, {{0, 1, 2, 3}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}}};
  m.vertices[0].x = std::bit_cast<float>(0xBF00000Au);  // about -0.5, its low byte first in the file
  const std::string scene = path("scan.ply");
  std::ofstream(scene, std::ios::binary) << test::plyFile(m, {.stanfordExtras = true});
  const std::string hits = path("h.exr");
  const RunResult r = run("-s " + scene + " -r 1 -w 32 --hits " + hits);
  ASSERT_EQ(r.status, 0) << r.err;
  const Scene loaded = loadScene(scene);
  ASSERT_EQ(loaded.triangles.size(), 5u);
  EXPECT_EQ(loaded.triangles[0].v0.x, m.vertices[0].x);
  test::expectHitsMatchBruteForce(hits, loaded, 32);
}

// Assimp clamped the index to the last vertex and rendered the file.
TEST_F(PlyCli, OffFaceNamingAMissingVertexIsAnError) {
  const RunResult r = run("-r 1 -s " + (kPlyData / "index_out_of_range.off").string() + " -w 8 -o " + path("out.png"));
  EXPECT_EQ(r.status, 1);
  expectOneLineError(r, "index_out_of_range.off:6: face 0 names vertex 7 of 3");
}

}  // namespace
}  // namespace passtrace
