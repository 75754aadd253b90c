// Issue 37: every registry row on every ray tracer equals brute force on the
// primary hits of each real scene (conference, sibenik, sponza, teapot,
// dragon; scenes/real_scenes.h), from its standard view, 16 x 16 pixels.
// Skipped with a message where ../shared/scenes/real is absent.
//
// One test per (scene, ray tracer): it loads the scene and computes brute
// force once, then runs each row through the command line. The rows run with
// their defaults and, for DACRT, also its conic packets (the DACRT path the
// seed measures); the other variant flags (loop limits, stack sizes,
// builders) run on Cornell, the bunny and BART (cli_every_structure_test.cpp).
// `-t 1`: one Goldsmith/Salmon insertion try, not ten (30 s on the dragon);
// the rows that do not read it warn, which is harmless here.
// On the scenes of more than kWholeMatrixTriangles (conference, dragon) each
// family runs its first row on each ray tracer, as the BART matrix does
// (testing_registry::representsItsFamily): every row over the dragon's 871K
// triangles was 4.4 minutes of the suite's CPU time. PASSTRACE_FULL_MATRIX=1
// runs every row there too.

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "scenes/real_scenes.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/real_scenes_dir.h"
#include "tests/registry_helpers.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

constexpr int kSize = 16;
constexpr size_t kWholeMatrixTriangles = 300000;

class EveryRowOnRealScenes : public test::CliTest,
                             public ::testing::WithParamInterface<std::tuple<std::string, RendererId>> {};

TEST_P(EveryRowOnRealScenes, HitBuffersEqualBruteForce) {
  const fs::path dir = test::realScenesDir();
  if (dir.empty()) GTEST_SKIP() << test::kRealScenesAbsent;
  const auto& [name, renderer] = GetParam();
  const Scene scene = loadScene(name, test::realSceneOptions(dir));
  const std::vector<Hit> expected = test::bruteForceHits(scene, kSize, kSize);
  const bool everyRow = testing_registry::fullMatrix() || scene.triangles.size() <= kWholeMatrixTriangles;
  int runs = 0;
  for (const auto& [r, accel] : testing_registry::everyStructureRun()) {
    if (RendererId(r) != renderer) continue;
    if (accel.find(' ') != std::string::npos && accel.find("--dacrt-cones") == std::string::npos) continue;
    if (!everyRow && !testing_registry::representsItsFamily({r, accel})) continue;
    const std::string file = path("h.exr");
    const test::RunResult result = run("-s " + name + " --scenes-dir " + dir.string() + " -b 1 -t 1 -w " +
                                       std::to_string(kSize) + " -r " + std::to_string(r) + " -a " + accel +
                                       " --hits " + file);
    SCOPED_TRACE(name + " -r " + std::to_string(r) + " -a " + accel);
    ASSERT_EQ(result.status, 0) << result.err;
    test::expectHitsMatch(file, expected, kSize, kSize);
    ++runs;
  }
  EXPECT_GT(runs, 0) << "no registry row runs on " << rendererName(renderer);
}

std::vector<std::tuple<std::string, RendererId>> sceneAndRenderer() {
  std::vector<std::tuple<std::string, RendererId>> params;
  for (const RealScene& s : realScenes())
    for (RendererId r : {RendererId::Cpu, RendererId::Gpu, RendererId::Embree})
      if (r != RendererId::Embree || std::any_of(structures().begin(), structures().end(),
                                                  [](const Structure& st) { return st.runsOn(RendererId::Embree); }))
        params.emplace_back(std::string(s.name), r);
  return params;
}

INSTANTIATE_TEST_SUITE_P(Real, EveryRowOnRealScenes, ::testing::ValuesIn(sceneAndRenderer()), [](const auto& info) {
  return std::get<0>(info.param) + "_" + std::string(rendererName(std::get<1>(info.param)));
});

}  // namespace
}  // namespace passtrace
