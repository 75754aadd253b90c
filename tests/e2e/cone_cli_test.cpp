// --cone through the command line (issue 16): kd-tree and BVH buffers agree
// on the bunny at 128^2 (0.5 degrees; 2.5 degrees and Kitchen are in
// tests/slow/cone_bart_test.cpp), the JSON's cone statistics, and the bad
// values' one-line errors.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"
#include "tests/cone_checks.h"

namespace passtrace {
namespace {

using test::RunResult;
using Cli = test::CliTest;

TEST_F(Cli, ConeKdTreeAndBvhAgreeOnTheBunny) {
  for (const char* accel : {"kd-tree", "kk-bvh"}) {
    const RunResult r = run(std::string("-s bunny -r 1 -w 128 --cone 0.5 -a ") + accel + " --cone-hits " +
                            path(std::string(accel) + ".exr") + " --json " + path(std::string(accel) + ".json"));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  test::expectConeBuffersAgree(path("kd-tree.exr"), path("kk-bvh.exr"), 128);
  for (const char* accel : {"kd-tree", "kk-bvh"}) {
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(path(std::string(accel) + ".json")));
    ASSERT_TRUE(j.contains("cone")) << accel;
    EXPECT_EQ(j["cone"]["half_angle_degrees"].get<double>(), 0.5);
    EXPECT_GT(j["cone"]["nodes_per_pixel"].get<double>(), 1.0);
    EXPECT_GE(j["cone"]["nodes_per_pixel_max"].get<double>(), j["cone"]["nodes_per_pixel"].get<double>());
    EXPECT_GE(j["cone"]["met_per_pixel_max"].get<double>(), 1.0);
  }
}

TEST_F(Cli, ConeMaxCapsTheCountAndKeepsTheNearest) {
  for (const char* max : {"0", "2"}) {
    const RunResult r = run(std::string("-s bunny -r 1 -w 48 --cone 1 -a kd-tree --cone-max ") + max +
                            " --cone-hits " + path(std::string("m") + max + ".exr"));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  int w = 0, h = 0;
  const std::vector<ConeHitRecord> all = readConeHitBuffer(path("m0.exr"), w, h);
  const std::vector<ConeHitRecord> two = readConeHitBuffer(path("m2.exr"), w, h);
  size_t capped = 0;
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(two[i].count, std::min(all[i].count, 2u)) << "pixel " << i;
    EXPECT_EQ(two[i].id, all[i].id) << "pixel " << i;
    EXPECT_EQ(two[i].t, all[i].t) << "pixel " << i;
    capped += all[i].count > 2;
  }
  EXPECT_GT(capped, 0u);
}

TEST_F(Cli, ConeBadValuesAreOneLineErrors) {
  const std::string out = " --cone-hits " + path("c.exr");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone -1" + out), "--cone");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone 90" + out), "--cone");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone nan" + out), "--cone");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone abc" + out), "--cone");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a grid --cone 1" + out), "kk-bvh, kd-tree");
  expectOneLineError(run("-s cornell -r 2 -w 8 -a kd-restart --cone 1" + out), "--cone");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree" + out), "--cone-hits");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone-max 3"), "--cone-max");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone 1 --cone-max -2" + out), "--cone-max");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone 1 --cone-hits " + path("c.png")), "--cone-hits");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone 1 -o " + path("c.png") + out), "-o");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kk-bvh --cone 1 --cone-nodes heap" + out), "--cone-nodes");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kk-bvh --cone-nodes sorted" + out), "--cone-nodes");
}

// The stream path (-r 2, kd-stack's tree = kd-tree's) gives the CPU's buffers
// exactly, and the same nodes and triangles per pixel; a list that overflows
// --cone-capacity is a one-line error.
TEST_F(Cli, ConeStreamPathEqualsCpuOnTheBunny) {
  const std::string cpu = path("cpu.exr"), gpu = path("gpu.exr");
  RunResult r = run("-s bunny -r 1 -w 64 --cone 0.5 -a kd-tree --cone-hits " + cpu + " --json " + path("cpu.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("-s bunny -r 2 -w 64 -l 3 --cone 0.5 -a kd-stack --cone-hits " + gpu + " --json " + path("gpu.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  test::expectConeBuffersEqual(cpu, gpu, 64);
  const nlohmann::json a = nlohmann::json::parse(std::ifstream(path("cpu.json")));
  const nlohmann::json b = nlohmann::json::parse(std::ifstream(path("gpu.json")));
  EXPECT_EQ(a["cone"]["nodes_per_pixel"], b["cone"]["nodes_per_pixel"]);
  EXPECT_EQ(a["cone"]["triangles_per_pixel"], b["cone"]["triangles_per_pixel"]);
  EXPECT_EQ(a["cone"]["met_per_pixel"], b["cone"]["met_per_pixel"]);
  for (const char* f : {"cpu.exr", "gpu.exr", "cpu.json", "gpu.json"}) std::filesystem::remove(path(f));
  expectOneLineError(run("-s cornell -r 2 -w 8 -a kd-stack --cone 30 --cone-capacity 1 --cone-hits " + gpu),
                     "--cone-capacity");
  expectOneLineError(run("-s cornell -r 2 -w 8 -a kd-stack --cone 30 --cone-max 5 --cone-capacity 4 --cone-hits " +
                         gpu), "--cone-max");
  expectOneLineError(run("-s cornell -r 1 -w 8 -a kd-tree --cone-capacity 4"), "--cone-capacity");
}

}  // namespace
}  // namespace passtrace
