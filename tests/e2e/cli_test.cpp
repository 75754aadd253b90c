// The passtrace command line end to end: outputs, the JSON contract, hit
// buffers against brute force, and one clear error for every bad input.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "accel/brute_force.h"
#include "render/camera.h"
#include "render/image_output.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::RunResult;
using test::slurp;
using Cli = test::CliTest;

TEST_F(Cli, HelpExplainsEveryThesisFlag) {
  const RunResult r = run("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* flag : {"-r,", "-a,", "-s,", "-w,", "-b,", "-p,", "-t,", "-g,", "-e,", "-d,", "-m,", "-n,", "-l,",
                           "-c,", "--eye", "--look-at", "--up", "--fov", "--hits", "--json", "--gl-backend", "--width",
                           "--height", "-o,"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST_F(Cli, HelpGroupsTheFlagsBeforeTheCatalog) {
  const RunResult r = run("--help");
  ASSERT_EQ(r.status, 0);
  const size_t catalog = r.out.find("Structures");
  ASSERT_NE(catalog, std::string::npos) << r.out;
  size_t previous = 0;
  for (const char* group : {"Scene and camera:", "Image and outputs:", "Renderer and structure:", "Build parameters",
                            "Shading and ray mixes:", "GPU stream path", "Sequences and dynamic scenes:",
                            "Seed-specific", "Run control:"}) {
    const size_t at = r.out.find(group);
    ASSERT_NE(at, std::string::npos) << group;
    EXPECT_GT(at, previous) << group << " out of order";
    EXPECT_LT(at, catalog) << group << " after the catalog";
    previous = at;
  }
  EXPECT_EQ(r.out.find("Options:"), std::string::npos) << "a flag outside every group";
}

void expectJsonContract(const nlohmann::json& j, const std::string& renderer) {
  for (const char* key : {"scene", "triangles", "renderer", "accelerator", "width", "height", "bounces", "rays",
                          "build_ms", "frame_ms", "mrays_per_s", "passes", "accel_floats_per_triangle", "gl_renderer"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["renderer"], renderer);
  EXPECT_EQ(j["scene"], "cornell");
  EXPECT_EQ(j["triangles"], 32);
  EXPECT_EQ(j["width"], 40);
  EXPECT_EQ(j["height"], 30);
  EXPECT_EQ(j["bounces"], 2);
  // Every primary ray hits the closed box; diffuse hits facing the light add shadow rays.
  EXPECT_GT(j["rays"].get<double>(), 1200.0);
  EXPECT_LE(j["rays"].get<double>(), 2400.0);
  EXPECT_GT(j["frame_ms"].get<double>(), 0.0);
  EXPECT_NEAR(j["mrays_per_s"].get<double>(), j["rays"].get<double>() / j["frame_ms"].get<double>() / 1000.0, 1e-9);
  if (renderer != "embree") {  // Embree does not say how much memory it uses
    EXPECT_NEAR(j["accel_floats_per_triangle"].get<double>(), 8.0 * 31 / 32, 1e-6);
  }
}

TEST_F(Cli, GpuRendererWritesImageAndJson) {
  const RunResult r = run("-s cornell -r 2 --width 40 --height 30 -b 2 -m 2 -o " + path("c.png") + " --json " +
                          path("c.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Mrays/s"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(path("c.json")));
  expectJsonContract(j, "gpu");
  EXPECT_TRUE(j["gl_renderer"].is_string());
  EXPECT_GE(j["passes"].get<double>(), 2.0);
  EXPECT_TRUE(fs::exists(path("c.png")));
}

TEST_F(Cli, CpuRendererWritesImageAndJson) {
  const RunResult r = run("-s cornell -r 1 --width 40 --height 30 -b 2 -o " + path("c.exr") + " --json " +
                          path("c.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  expectJsonContract(nlohmann::json::parse(slurp(path("c.json"))), "cpu");
  EXPECT_TRUE(fs::exists(path("c.exr")));
  if (!PASSTRACE_HAVE_EMBREE) {  // then -r 3 is a one-line error
    fs::remove(path("c.exr"));
    fs::remove(path("c.json"));
    expectOneLineError(run("-s cornell -r 3 --width 40 --height 30 -b 2"), "built without Embree");
    return;
  }
  const RunResult embree = run("-s cornell -r 3 --width 40 --height 30 -b 2 --json " + path("e.json"));
  ASSERT_EQ(embree.status, 0) << embree.err;
  expectJsonContract(nlohmann::json::parse(slurp(path("e.json"))), "embree");
}

TEST_F(Cli, StatsAndHeatmapDescribeTheTraversal) {
  const RunResult r = run("-s cornell -r 2 -a kd-backtrack -w 32 -b 2 --stats --heatmap " + path("heat.png") +
                          " --json " + path("s.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("floats/triangle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("traversal steps"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(path("heat.png")));
  const auto j = nlohmann::json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["accelerator"], "kd-backtrack");
  EXPECT_GT(j["steps_per_ray"].get<double>(), 1.0);
  EXPECT_GT(j["triangle_tests_per_ray"].get<double>(), 0.0);
  // A pixel's rays take at least the mean of all rays'.
  EXPECT_GE(j["max_steps_per_ray"].get<double>(), j["steps_per_ray"].get<double>());
  EXPECT_GE(j["max_triangle_tests_per_ray"].get<double>(), j["triangle_tests_per_ray"].get<double>());
  EXPECT_NE(r.out.find("max per pixel (all its rays): "), std::string::npos) << r.out;
  EXPECT_GE(j["accel_nodes"].get<double>(), 1.0);
  EXPECT_GE(j["accel_references"].get<double>(), 32.0);
  // The kd rows' cost and memory: every ray through the box costs at least one node step.
  EXPECT_NE(r.out.find("SAH cost"), std::string::npos) << r.out;
  EXPECT_GE(j["structure"]["sah_cost"].get<double>(), 1.0);
  EXPECT_GE(j["structure"]["structure_bytes"].get<double>(), 16.0 * 3 * j["accel_nodes"].get<double>());
  EXPECT_EQ(j["structure"]["node_test_bytes"], 0);  // not stated by the kd rows
  fs::remove(path("heat.png"));
  fs::remove(path("s.json"));
  expectOneLineError(run("-s cornell -r 0 --heatmap " + path("h.png")), "--heatmap");
}

// What a node test and a triangle test read (the scaling report's bytes per
// ray): the 8-wide node of eight float boxes and links, a quarter of a pack of
// four triangles (vertex and two edges), for both rows that state them.
TEST_F(Cli, JsonStatesBytesPerTestWhereTheRowKnowsThem) {
  for (const std::string row : {"bvh8", "bvh8-packet"}) {
    const RunResult r = run("-s cornell -r 1 -a " + row + " -w 32 -b 1 --json " + path("b.json"));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(path("b.json")));
    EXPECT_EQ(j["structure"]["node_test_bytes"], 8 * 6 * 4 + 8 * 4) << row;
    EXPECT_EQ(j["structure"]["triangle_test_bytes"], 10 * 4) << row;
    fs::remove(path("b.json"));
  }
}

TEST_F(Cli, PreviewRendererWritesImage) {
  const RunResult r = run("-s cornell -r 0 -w 32 -o " + path("p.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("p.png")));
}

TEST_F(Cli, DumpImagesWritesOneImagePerAngle) {
  const RunResult r = run("-s cornell -r 1 -w 16 -n 3 -p -o " + path("a.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"a.png", "a_0.png", "a_1.png", "a_2.png"}) EXPECT_TRUE(fs::exists(path(name))) << name;
}

TEST_F(Cli, CameraPathGivesDistinctViewsExceptForFixedViewScenes) {
  RunResult r = run("-s bunny -r 1 -b 1 -w 32 -n 100 -p -o " + path("b.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::set<std::string> images;
  for (int k = 0; k < 100; ++k) images.insert(slurp(path("b_" + std::to_string(k) + ".png")));
  EXPECT_EQ(images.size(), 100u) << "every angle of the path shows the bunny differently";
  r = run("-s cornell -r 1 -b 1 -w 12 -n 3 -p -o " + path("c.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(path("c_0.png")), slurp(path("c_2.png"))) << "the Cornell box keeps its one view (thesis 10.1.1)";
}

// The hit buffers of both ray tracers against brute force on the contract's rays.
using test::expectHitsMatchBruteForce;

TEST_F(Cli, HitBuffersOfBothRaytracersEqualBruteForce) {
  const Scene bunny = loadScene("bunny");
  for (int renderer : {1, 2}) {
    const std::string file = path(renderer == 1 ? "h1.exr" : "h2.exr");
    const RunResult r = run("-s bunny -b 1 -w 48 -r " + std::to_string(renderer) + " --hits " + file);
    ASSERT_EQ(r.status, 0) << r.err;
    SCOPED_TRACE("-r " + std::to_string(renderer));
    expectHitsMatchBruteForce(file, bunny, 48);
  }
}

TEST_F(Cli, BadInputsGiveOneLineErrorsAndNoOutput) {
  std::ofstream(path("bad.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const std::string outs = " -o " + path("x.png") + " --json " + path("x.json");
  expectOneLineError(run("-s " + path("missing.obj") + outs), "missing.obj");
  expectOneLineError(run("-s nosuchscene" + outs), "nosuchscene");
  expectOneLineError(run("-s " + path("bad.obj") + outs), "bad.obj:4");
  expectOneLineError(run("-s cornell -w abc" + outs), "abc");
  expectOneLineError(run("-s cornell -w 0" + outs), "--resolution");
  expectOneLineError(run("-s cornell -r 1 --width 20000 --height 20000" + outs), "too large");
  expectOneLineError(run("-s cornell -r 2 -w 20000" + outs), "GL limit");
  expectOneLineError(run("-s cornell -r 2 -w 100000" + outs), "--resolution");
  expectOneLineError(run("-s cornell -a 9" + outs), "9");
  expectOneLineError(run("-s cornell -a nosuchaccel" + outs), "nosuchaccel");
  expectOneLineError(run("-s cornell -r 2 -a 5" + outs), "unknown accelerator '5' (valid on the GPU stream renderer");
  expectOneLineError(run("-s cornell -r 2 -a kd-tree" + outs), "kd-tree");
  expectOneLineError(run("-s cornell -r 7" + outs), "-r");
  for (const char* k : {"0", "9", "x", "2.5"})
    expectOneLineError(run("-s cornell -a kd-shortstack --stack-size " + std::string(k) + outs), "--stack-size");
  expectOneLineError(run("-s cornell -r 1 -a kd-tree --kd-builder fast" + outs), "--kd-builder");
  expectOneLineError(run("-s cornell -r 1 -a kd-tree --kd-termination x" + outs), "--kd-termination");
  expectOneLineError(run("-s cornell -r 1 -a dacrt --dacrt-rlimit 0" + outs), "--dacrt-rlimit");
  expectOneLineError(run("-s cornell -r 1 -a dacrt --dacrt-plimit -1" + outs), "--dacrt-plimit");
  expectOneLineError(run("-s cornell -r 1 -a dacrt --dacrt-split middle" + outs), "--dacrt-split");
  expectOneLineError(run("-s cornell -r 1 -a bvh-stack --bvh-builder kd" + outs), "--bvh-builder");
  expectOneLineError(run("-s cornell -r 1 -a bvh8 --bvh8-builder sah" + outs), "--bvh8-builder");
  expectOneLineError(run("-s cornell -r 1 -w 20000 -o " + path("x.png")), "too large");
  expectOneLineError(run("-s cornell --eye 1,2" + outs), "--eye");
  expectOneLineError(run("-s cornell --eye 1,2,nan" + outs), "--eye");
  expectOneLineError(run("-s cornell --eye 278,273,0 --look-at 278,273,0" + outs), "coincide");
  expectOneLineError(run("-s cornell --up 0,0,1 --eye 0,0,0 --look-at 0,0,5" + outs), "parallel");
  expectOneLineError(run("-s cornell --gl-backend vulkan" + outs), "vulkan");
  expectOneLineError(run("-s cornell -o " + path("no/such/dir/x.png")), "does not exist");
  expectOneLineError(run("-s cornell -o " + path("x.unknownformat")), "x.unknownformat");
  expectOneLineError(run("-s cornell --hits " + path("h.png")), ".exr");
  expectOneLineError(run("-s cornell --unknown-flag" + outs), "unknown-flag");
}

TEST_F(Cli, NoGlContextIsAnErrorAndAutoFallsBackToOsMesa) {
  // Pointing glvnd at no vendor library leaves EGL without a driver.
  const std::string noEgl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json";
  expectOneLineError(run("-s cornell -w 16 --gl-backend egl -o " + path("x.png"), noEgl), "no OpenGL 4.5 context");
  if (!PASSTRACE_HAVE_OSMESA) {  // no fallback then, and asking for OSMesa is a one-line error
    expectOneLineError(run("-s cornell -w 16 --gl-backend osmesa -o " + path("x.png")), "built without OSMesa");
    GTEST_SKIP() << "passtrace was built without OSMesa";
  }
  const RunResult r = run("-s cornell -w 16 --gl-backend auto --json " + path("j.json"), noEgl);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("falling back to OSMesa"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(path("j.json")))["gl_backend"], "osmesa");
}

}  // namespace
}  // namespace passtrace
