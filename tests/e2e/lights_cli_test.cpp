// Lights on the command line: --light replaces the file's lights, a file
// without lights seen from inside its bounds gets a headlight and is lit
// (scenes/scene_lights.h), seen from outside it keeps the framed light, and a
// bad --light is a one-line error with no output.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/image_output.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/real_scenes_dir.h"

namespace passtrace {
namespace {

using test::litFraction;
using test::RunResult;
using LightsCli = test::CliTest;

// A closed room [0,10]^3 (walls facing in) with a table-like box inside; no lights in the file.
std::string writeRoom(const std::string& file) {
  std::ofstream out(file);
  const auto box = [&](float x0, float y0, float z0, float x1, float y1, float z1, int base) {
    for (float x : {x0, x1})
      for (float y : {y0, y1})
        for (float z : {z0, z1}) out << "v " << x << ' ' << y << ' ' << z << "\n";
    // Corners 1..8 in x-major order; six quads as two triangles each.
    const int q[6][4] = {{1, 2, 4, 3}, {5, 7, 8, 6}, {1, 5, 6, 2}, {3, 4, 8, 7}, {1, 3, 7, 5}, {2, 6, 8, 4}};
    for (const auto& f : q)
      out << "f " << base + f[0] << ' ' << base + f[1] << ' ' << base + f[2] << "\nf " << base + f[0] << ' '
          << base + f[2] << ' ' << base + f[3] << "\n";
  };
  box(0, 0, 0, 10, 10, 10, 0);
  box(3, 0, 3, 7, 3, 7, 8);
  return file;
}

TEST_F(LightsCli, AFileWithoutLightsSeenFromInsideIsLitOnBothRenderers) {
  const std::string room = writeRoom(path("room.obj"));
  const std::string inside = " --eye 8,6,9 --look-at 4,2,2 -b 2 -w 48 -a kk-bvh";
  for (const char* renderer : {"1", "2"}) {
    SCOPED_TRACE(renderer);
    const std::string image = path(std::string("inside") + renderer + ".exr");
    const RunResult r = run("-s " + room + inside + " -r " + renderer + " -o " + image);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GE(litFraction(image), 0.5);
    // The light framed outside the walls, given by hand, leaves the inside dark:
    // what the headlight replaces.
    const glm::vec3 outside = framedLight(loadScene(room).bounds()).position;
    const std::string dark = path(std::string("dark") + renderer + ".exr");
    const RunResult d = run("-s " + room + inside + " -r " + renderer + " -o " + dark + " --light " +
                            std::to_string(outside.x) + "," + std::to_string(outside.y) + "," + std::to_string(outside.z));
    ASSERT_EQ(d.status, 0) << d.err;
    EXPECT_LT(litFraction(dark), 0.1);
  }
}

TEST_F(LightsCli, SeenFromOutsideAFileKeepsItsFramedLight) {
  const std::string bunny = " -s bunny -r 1 -b 2 -w 32 -a kk-bvh -o ";
  ASSERT_EQ(run(bunny + path("default.exr")).status, 0);
  const glm::vec3 framed = loadScene("bunny").light.position;
  const std::string at = std::to_string(framed.x) + "," + std::to_string(framed.y) + "," + std::to_string(framed.z);
  // %f rounds the position: compare images by lit fraction, not bytes.
  ASSERT_EQ(run(bunny + path("given.exr") + " --light " + at).status, 0);
  EXPECT_NEAR(litFraction(path("default.exr")), litFraction(path("given.exr")), 0.01);
}

TEST_F(LightsCli, SeveralLightsReplaceTheFilesAndEachCounts) {
  const std::string room = writeRoom(path("room.obj"));
  const std::string base = "-s " + room + " --eye 8,6,9 --look-at 4,2,2 -r 1 -b 2 -w 32 --shading whitted -o ";
  ASSERT_EQ(run(base + path("one.exr") + " --light 9,9,9").status, 0);
  ASSERT_EQ(run(base + path("two.exr") + " --light 9,9,9 --light 1,9,1").status, 0);
  EXPECT_NE(test::slurp(path("one.exr")), test::slurp(path("two.exr")));
}

TEST_F(LightsCli, BadLightIsOneLineErrorWithNoOutput) {
  const std::string outs = " -s cornell -r 1 -w 8 -o " + path("x.png") + " --json " + path("x.json");
  expectOneLineError(run("--light 1,2" + outs), "--light");
  expectOneLineError(run("--light 1,2,nan" + outs), "--light");
  expectOneLineError(run("--light" + outs), "--light");
}

// The case: the Conference room seen from inside, default shading, -b 2.
TEST_F(LightsCli, TheConferenceRoomSeenFromInsideIsLit) {
  const std::filesystem::path dir = test::realScenesDir();
  if (dir.empty()) GTEST_SKIP() << test::kRealScenesAbsent;
  const std::string image = path("conference.exr");
  const RunResult r = run("-s " + (dir / "conference" / "conference.ply").string() +
                          " --eye 1500,450,500 --look-at 0,150,-300 -r 1 -a bvh8 -b 2 -w 64 -o " + image);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GE(litFraction(image), 0.5);
}

}  // namespace
}  // namespace passtrace
