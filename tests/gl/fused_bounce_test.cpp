// bvh-octant-fused (GpuTraversal::fusedBounce): a primary bounce as one pass
// of ray generation, the octant walk and thesis shading must leave what
// bvh-octant's raygen, traversal and shading passes leave, bit for bit:
// image, per-pixel steps, the frame's counts and the primary hits. Checked
// where the fused pass runs (-b 1 with and without --hits, -b 3), where a
// loop limit too small for one pass sends the bounce back to the passes,
// and where it does not apply (AO shading, --hits past one bounce, an -l
// below the pass's budget).

#include <gtest/gtest.h>

#include <ostream>

#include "accel/registry.h"
#include "render/gpu_renderer.h"
#include "scenes/scene_registry.h"
#include "tests/frame_checks.h"
#include "tests/gl_test_support.h"

namespace passtrace {
namespace {

struct Frame {
  FrameResult result;
  bool fused;
};

Frame render(const Scene& scene, GpuTraversal& traversal, int size, ShadingMode mode, int bounces, bool hits) {
  ShadingConfig shading;
  shading.mode = mode;
  GpuRenderer renderer(scene, traversal, size, size + 3, 0, shading);  // not square: rows and columns differ
  FrameResult result = renderer.render(scene.camera, bounces, hits);
  return {std::move(result), renderer.lastFrameFused()};
}

struct Case {
  const char* scene;
  ShadingMode mode;
  int bounces;
  bool hits;
  int loopLimit;          // 0: one pass per bounce
  bool onePassPerBounce;  // as -l 0 sets it; with a small loopLimit, as if the budget were that small
  bool fused;             // whether the fused pass serves the primary bounce
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.scene << " " << shadingModeName(c.mode) << " -b " << c.bounces << (c.hits ? " --hits" : "") << " -l "
      << c.loopLimit;
}

class FusedBounce : public test::GlTest, public ::testing::WithParamInterface<Case> {};

TEST_P(FusedBounce, LeavesWhatThePassesLeave) {
  const Case c = GetParam();
  const Scene scene = loadScene(c.scene);
  GpuTraversalConfig config;
  config.loopLimit = c.loopLimit;
  config.onePassPerBounce = c.onePassPerBounce;
  config = withPassStepLimit(config);
  const auto fused = makeStreamStructure("bvh-octant-fused", scene.triangles, config);
  const auto passes = makeStreamStructure("bvh-octant", scene.triangles, config);
  ASSERT_EQ(fused->fusedBounce() != nullptr, c.onePassPerBounce || c.loopLimit == 0);
  ASSERT_EQ(passes->fusedBounce(), nullptr);
  const Frame got = render(scene, *fused, 41, c.mode, c.bounces, c.hits);
  const Frame want = render(scene, *passes, 41, c.mode, c.bounces, c.hits);
  EXPECT_EQ(got.fused, c.fused);
  EXPECT_FALSE(want.fused);
  EXPECT_GT(got.result.stats.steps, 0u);
  test::expectSameFrame(got.result, want.result);
}

INSTANTIATE_TEST_SUITE_P(
    Frames, FusedBounce,
    ::testing::Values(Case{"bunny", ShadingMode::Thesis, 1, false, 0, false, true},
                      Case{"bunny", ShadingMode::Thesis, 1, true, 0, false, true},
                      Case{"cornell", ShadingMode::Thesis, 1, true, 0, false, true},
                      Case{"cornell", ShadingMode::Thesis, 3, false, 0, false, true},  // shadow and mirror rays follow
                      Case{"cornell", ShadingMode::Thesis, 3, true, 0, false, false},  // hits would be shaded over
                      Case{"cornell", ShadingMode::Thesis, 1, true, 3, true, false},   // rays left unfinished
                      Case{"cornell", ShadingMode::Thesis, 1, false, 3, false, false},  // -l 3: not offered
                      Case{"cornell", ShadingMode::Ao, 2, false, 0, false, false}),    // not thesis shading
    [](const auto& info) {
      const Case& c = info.param;
      return std::string(c.scene) + "_" + shadingModeName(c.mode) + "_b" + std::to_string(c.bounces) +
             (c.hits ? "_hits" : "") + "_l" + std::to_string(c.loopLimit) + (c.onePassPerBounce ? "_budget" : "");
    });

}  // namespace
}  // namespace passtrace
