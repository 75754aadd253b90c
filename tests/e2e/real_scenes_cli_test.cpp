// The real benchmark scenes by name (scenes/real_scenes.h): found through
// --scenes-dir, $PASSTRACE_SCENES_DIR or ../shared/scenes/real, listed by
// --list --json when found, a one-line error naming the places when not, and
// each with its standard view and light. The tests with stand-in files run
// everywhere; those on the real copies skip where ../shared is absent.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scenes/real_scenes.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/real_scenes_dir.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::RunResult;
using RealScenesCli = test::CliTest;

std::vector<std::string> listedScenes(const RunResult& r) {
  std::vector<std::string> names;
  const nlohmann::json catalog = nlohmann::json::parse(r.out);  // kept: the loop walks into it
  for (const nlohmann::json& s : catalog["scenes"]) names.push_back(s["name"]);
  return names;
}

// A stand-in for a real scene's file: a closed box, 12 triangles.
void writeBox(const fs::path& file) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file);
  for (int x : {-1, 1})
    for (int y : {-1, 1})
      for (int z : {-1, 1}) out << "v " << x << ' ' << y << ' ' << z << "\n";
  const int q[6][4] = {{1, 2, 4, 3}, {5, 7, 8, 6}, {1, 5, 6, 2}, {3, 4, 8, 7}, {1, 3, 7, 5}, {2, 6, 8, 4}};
  for (const auto& f : q) out << "f " << f[0] << ' ' << f[1] << ' ' << f[2] << "\nf " << f[0] << ' ' << f[2] << ' ' << f[3] << "\n";
}

TEST_F(RealScenesCli, ListedWhereTheirFilesAreAndOnlyThose) {
  const fs::path dir = path("real");
  writeBox(dir / "teapot" / "teapot.obj");
  RunResult r = run("--list --json --scenes-dir " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> names = listedScenes(r);
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.back(), "teapot");
  EXPECT_EQ(std::count(names.begin(), names.end(), "dragon"), 0);
  // The environment variable does the same; --scenes-dir wins over it.
  r = run("--list --json", "PASSTRACE_SCENES_DIR=" + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(listedScenes(r).back(), "teapot");
  fs::create_directory(path("empty"));
  r = run("--list --json --scenes-dir " + path("empty"), "PASSTRACE_SCENES_DIR=" + dir.string());
  EXPECT_EQ(listedScenes(r).back(), "spheres");
}

TEST_F(RealScenesCli, AnotherCopyLoadsWithAWarningAndTheStandardView) {
  const fs::path dir = path("real");
  writeBox(dir / "teapot" / "teapot.obj");
  const RunResult r = run("-s teapot --scenes-dir " + dir.string() + " -r 1 -a bvh8 -w 16 --json " + path("t.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("passtrace: warning: teapot: 12 triangles, not the documented copy's 6320"), std::string::npos)
      << r.err;
  std::ifstream in(path("t.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["scene"], "teapot");
  EXPECT_EQ(j["triangles"], 12);
}

TEST_F(RealScenesCli, NotFoundIsOneLineErrorNamingWhereItLooked) {
  const std::string outs = " -w 8 -o " + path("x.png") + " --json " + path("x.json");
  fs::create_directory(path("empty"));
  RunResult r = run("-s sibenik --scenes-dir " + path("empty") + outs);
  expectOneLineError(r, "--scenes-dir");
  EXPECT_NE(r.err.find("sibenik/sibenik.ply not found"), std::string::npos) << r.err;
  r = run("-s sponza" + outs, "PASSTRACE_SCENES_DIR=" + path("nowhere"));
  expectOneLineError(r, "$PASSTRACE_SCENES_DIR");
  // With nothing set and no ../shared beside the current directory or the
  // executable: the binary copied into the test's directory, run from there.
  fs::copy_file(test::passtraceBinary(), path("passtrace"));
  const std::string alone = "cd " + dir_.string() + " && env -u PASSTRACE_SCENES_DIR ./passtrace -s dragon" + outs +
                            " >" + path("out.txt") + " 2>" + path("err.txt");
  const int status = std::system(alone.c_str());
  EXPECT_NE(status, 0);
  const std::string err = test::slurp(path("err.txt"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  for (const char* place : {"--scenes-dir", "$PASSTRACE_SCENES_DIR", "../shared/scenes/real"})
    EXPECT_NE(err.find(place), std::string::npos) << place << " in " << err;
  EXPECT_FALSE(fs::exists(path("x.png")));
  EXPECT_FALSE(fs::exists(path("x.json")));
}

// The check: the five real copies by name, their exact triangle counts.
TEST_F(RealScenesCli, TheFiveRealScenesLoadWithTheirCounts) {
  const fs::path dir = test::realScenesDir();
  if (dir.empty()) GTEST_SKIP() << test::kRealScenesAbsent;
  RunResult r = run("--list --json", "PASSTRACE_SCENES_DIR=" + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> names = listedScenes(r);
  for (const RealScene& s : realScenes()) {
    SCOPED_TRACE(std::string(s.name));
    EXPECT_EQ(std::count(names.begin(), names.end(), std::string(s.name)), 1);
    const Scene scene = loadScene(std::string(s.name), test::realSceneOptions(dir));
    EXPECT_EQ(scene.triangles.size(), s.triangles);
    EXPECT_EQ(scene.name, s.name);
  }
  EXPECT_EQ(findRealScene("conference")->triangles, 331'179u);
  EXPECT_EQ(findRealScene("sibenik")->triangles, 75'284u);
  EXPECT_EQ(findRealScene("sponza")->triangles, 69'063u);
  EXPECT_EQ(findRealScene("teapot")->triangles, 6'320u);
  EXPECT_EQ(findRealScene("dragon")->triangles, 871'414u);
}

bool inside(const Aabb& box, const glm::vec3& p) {
  return glm::all(glm::greaterThan(p, box.min)) && glm::all(glm::lessThan(p, box.max));
}

TEST_F(RealScenesCli, InteriorsAreSeenFromInsideAndLitOnBothRenderers) {
  const fs::path dir = test::realScenesDir();
  if (dir.empty()) GTEST_SKIP() << test::kRealScenesAbsent;
  for (const char* name : {"conference", "sibenik", "sponza"}) {
    const Scene scene = loadScene(name, test::realSceneOptions(dir));
    SCOPED_TRACE(name);
    EXPECT_TRUE(inside(scene.bounds(), scene.camera.eye));
    EXPECT_TRUE(inside(scene.bounds(), scene.light.position));
    EXPECT_TRUE(scene.fixedView);
    for (const char* renderer : {"1", "2"}) {
      const std::string image = path(std::string(name) + renderer + ".exr");
      const RunResult r = run("-s " + std::string(name) + " --scenes-dir " + dir.string() + " -r " + renderer +
                              " -a kk-bvh -b 2 -w 48 -o " + image);
      ASSERT_EQ(r.status, 0) << r.err;
      EXPECT_GE(test::litFraction(image), 0.5);
    }
  }
  // -n keeps working: the interiors keep their view, the objects follow the path.
  const RunResult n = run("-s sibenik --scenes-dir " + dir.string() + " -r 1 -a bvh8 -w 16 -n 3");
  EXPECT_EQ(n.status, 0) << n.err;
  const RunResult t = run("-s teapot --scenes-dir " + dir.string() + " -r 2 -a kk-bvh -w 16 -n 3");
  EXPECT_EQ(t.status, 0) << t.err;
}

}  // namespace
}  // namespace passtrace
