// What the command line says about itself: `passtrace --list --json` follows
// its contract (README) and lists every registry row, `--version` prints the
// version, and a build flag the chosen structure does not read is reported
// once as a warning (silenced by --quiet), for every row of the registry.

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "accel/registry.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

using test::RunResult;
using Cli = test::CliTest;

std::set<std::string> keysOf(const nlohmann::json& object) {
  std::set<std::string> keys;
  for (const auto& [key, value] : object.items()) keys.insert(key);
  return keys;
}

TEST_F(Cli, ListJsonFollowsTheContractAndTheRegistry) {
  // An empty --scenes-dir: the real scenes, found or not beside the checkout, are not listed.
  std::filesystem::create_directory(path("no-scenes"));
  const RunResult r = run("--list --json --scenes-dir " + path("no-scenes"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(keysOf(j), (std::set<std::string>{"version", "renderers", "accelerators", "scenes"}));
  EXPECT_TRUE(j["version"].is_string());

  const nlohmann::json renderers = {{{"name", "opengl"}, {"id", 0}},
                                    {{"name", "cpu"}, {"id", 1}},
                                    {{"name", "gpu"}, {"id", 2}},
                                    {{"name", "embree"}, {"id", 3}}};
  EXPECT_EQ(j["renderers"], renderers);

  // One entry per registry row, in registry order.
  const nlohmann::json& accelerators = j["accelerators"];
  ASSERT_TRUE(accelerators.is_array());
  ASSERT_EQ(accelerators.size(), structures().size());
  for (size_t i = 0; i < structures().size(); ++i) {
    const Structure& s = structures()[i];
    const nlohmann::json& a = accelerators[i];
    SCOPED_TRACE(std::string(s.name));
    EXPECT_EQ(keysOf(a),
              (std::set<std::string>{"name", "renderers", "number", "cpu_ray_groups", "featured", "description"}));
    EXPECT_EQ(a["name"], s.name);
    nlohmann::json on = nlohmann::json::array();
    for (RendererId renderer : kRenderers)
      if (s.runsOn(renderer)) on.push_back(rendererName(renderer));
    EXPECT_EQ(a["renderers"], on);
    EXPECT_EQ(a["number"], s.number ? nlohmann::json(*s.number) : nlohmann::json(nullptr));
    EXPECT_EQ(a["description"], s.description);
    EXPECT_EQ(a["cpu_ray_groups"], s.runsOn(RendererId::Cpu) ? nlohmann::json(rayGroupingName(s.cpuRayGrouping))
                                                              : nlohmann::json(nullptr));
    nlohmann::json featured = nlohmann::json::array();
    for (const Featured& f : s.featured)
      featured.push_back({{"report", reportName(f.report)}, {"renderer", rendererName(f.renderer)}});
    EXPECT_EQ(a["featured"], featured);
  }

  // The built-in scenes by name and thesis number, and the procedural one; no real scene.
  const nlohmann::json& scenes = j["scenes"];
  ASSERT_TRUE(scenes.is_array());
  for (const nlohmann::json& scene : scenes) {
    EXPECT_EQ(keysOf(scene), (std::set<std::string>{"name", "number"})) << scene;
    EXPECT_TRUE(scene["name"].is_string()) << scene;
    EXPECT_TRUE(scene["number"].is_number_integer() || scene["number"].is_null()) << scene;
  }
  const std::vector<std::string> builtin = builtinSceneNames();
  ASSERT_EQ(scenes.size(), builtin.size() + 1);
  for (size_t i = 0; i < builtin.size(); ++i) {
    EXPECT_EQ(scenes[i]["name"], builtin[i]);
    EXPECT_EQ(scenes[i]["number"], int(i));
  }
  EXPECT_EQ(scenes.back()["name"], "spheres");
  EXPECT_TRUE(scenes.back()["number"].is_null());
}

TEST_F(Cli, VersionPrintsTheProjectVersion) {
  const RunResult r = run("--version");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, std::string("passtrace ") + PASSTRACE_EXPECTED_VERSION + "\n");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(nlohmann::json::parse(run("--list --json").out)["version"], PASSTRACE_EXPECTED_VERSION);
}

TEST_F(Cli, AFlagTheStructureDoesNotReadIsOneWarning) {
  const std::string scene = "-s cornell -w 8 -b 1 -o " + path("x.png");
  RunResult r = run(scene + " -r 1 -a kd-tree -g 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("passtrace: warning: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("-g/--grid-multiplier"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("kd-tree"), std::string::npos) << r.err;
  r = run(scene + " -r 1 -a kd-tree -g 2 --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
}

// Every build parameter with a valid value for it on the command line.
const std::vector<std::pair<BuildParam, std::string>> kParamArgs = {
    {BuildParam::SwapChildren, "-c 1"},        {BuildParam::GsTries, "-t 2"},
    {BuildParam::GridMultiplier, "-g 2"},      {BuildParam::KdMinElements, "-e 3"},
    {BuildParam::KdMaxDepth, "-d 10"},         {BuildParam::GridKernels, "--grid-kernels split"},
    {BuildParam::LoopLimit, "-l 10"},          {BuildParam::PageTexels, "--page-texels 0"},
    {BuildParam::TriangleTest, "--triangle-test watertight"},
    {BuildParam::KdStackSize, "--stack-size 2"},
    {BuildParam::KdBuilder, "--kd-builder binned"},   {BuildParam::KdTermination, "--kd-termination papay"},
    {BuildParam::BvhBuilder, "--bvh-builder sbvh"},
    {BuildParam::Bvh8Builder, "--bvh8-builder sbvh"}};

// For each renderer of a row: the flags the row reads give no warning; the
// first flag it does not read gives exactly one, naming the flag.
class CliParams : public test::CliTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(CliParams, UnreadFlagsWarnOnceAndReadOnesDoNot) {
  const Structure& s = *findStructure(GetParam());
  for (const RendererId renderer : {RendererId::Cpu, RendererId::Gpu, RendererId::Embree}) {
    if (!s.runsOn(renderer)) continue;
    SCOPED_TRACE(std::string(rendererName(renderer)));
    const std::vector<BuildParam> reads = s.readsOn(renderer);
    const std::string common = "-s cornell -w 8 -b 1 -r " + std::to_string(int(renderer)) + " -a " +
                               std::string(s.name) + " -o " + path("x.png");
    std::string readArgs;
    const std::pair<BuildParam, std::string>* unread = nullptr;
    for (const auto& param : kParamArgs) {
      if (std::find(reads.begin(), reads.end(), param.first) != reads.end()) readArgs += " " + param.second;
      else if (!unread) unread = &param;
    }
    RunResult r = run(common + readArgs);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "") << readArgs;
    if (!unread) continue;
    r = run(common + " " + unread->second);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("passtrace: warning: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(buildParamFlag(unread->first)), std::string::npos) << r.err;
  }
}


INSTANTIATE_TEST_SUITE_P(AllStructures, CliParams, ::testing::ValuesIn(testing_registry::rowNames()),
                         testing_registry::CaseNameOfRow());

}  // namespace
}  // namespace passtrace
