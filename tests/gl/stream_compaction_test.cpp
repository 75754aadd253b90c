// --compact always and on (stream/stream_compaction.h): every stream row traces the
// same rays to the same results whether each generation's live rays are
// gathered into whole 4x4 blocks or not. Cornell 32x32 with Whitted shading
// (only mirror and glass pixels and lit hits continue, so later generations
// are sparse) at loop limit 3 (many passes per generation).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "accel/brute_force.h"
#include "accel/registry.h"
#include "render/camera.h"
#include "render/gpu_renderer.h"
#include "scenes/scene_registry.h"
#include "tests/frame_checks.h"
#include "tests/gl_test_support.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

using test::GlTest;

constexpr int kSize = 32;


FrameResult render(const Scene& scene, GpuTraversal& traversal, ShadingConfig shading, int bounces,
                   Compaction compact) {
  GpuRenderer renderer(scene, traversal, kSize, kSize, 0, shading, compact);
  return renderer.render(scene.camera, bounces, true);
}

class CompactOnOff : public test::GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(CompactOnOff, SameImageHitsAndCountsAsWithout) {
  const Scene scene = loadScene("cornell");
  GpuTraversalConfig config;
  config.loopLimit = 3;
  const auto traversal = makeStreamStructure(GetParam(), scene.triangles, config);
  for (const ShadingMode mode : {ShadingMode::Whitted, ShadingMode::Thesis}) {
    ShadingConfig shading;
    shading.mode = mode;
    const FrameResult off = render(scene, *traversal, shading, 3, Compaction::Off);
    const FrameResult on = render(scene, *traversal, shading, 3, Compaction::Always);
    SCOPED_TRACE(shadingModeName(mode));
    EXPECT_GT(on.stats.rays, uint64_t(kSize * kSize));  // secondary generations ran
    const FrameResult sparse = render(scene, *traversal, shading, 3, Compaction::On);  // later generations only
    EXPECT_EQ(sparse.rgb, off.rgb);
    EXPECT_EQ(sparse.steps, off.steps);
    test::expectSameFrame(on, off);
  }
}

// The compact run's primary hits against brute force over the CPU's camera rays
// (ties aside: the same t where the triangle differs).
TEST_P(CompactOnOff, PrimaryHitsEqualBruteForce) {
  const Scene scene = loadScene("cornell");
  GpuTraversalConfig config;
  config.loopLimit = 3;
  const auto traversal = makeStreamStructure(GetParam(), scene.triangles, config);
  const FrameResult on = render(scene, *traversal, ShadingConfig{}, 1, Compaction::Always);
  const CameraBasis basis = makeCameraBasis(scene.camera, kSize, kSize);
  int hits = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Hit brute = intersectBruteForce(scene.triangles, primaryRay(basis, x, y), false);
      const HitRecord gpu = on.primaryHits[size_t(y) * kSize + x];
      ASSERT_EQ(brute.found(), gpu.id != kNoHit) << x << "," << y;
      if (!brute.found()) continue;
      ++hits;
      EXPECT_NEAR(gpu.t, brute.t, 1e-4f * brute.t) << x << "," << y;
      if (std::abs(gpu.t - brute.t) > 1e-6f * brute.t) {  // not a tie: the same triangle
        EXPECT_EQ(gpu.id, brute.id) << x << "," << y;
      }
    }
  EXPECT_GT(hits, kSize * kSize / 2);
}

// A stream whose sides are not multiples of 4: the compact stream is wider
// (whole blocks) and its last block row partly padding.
TEST_F(GlTest, CompactionOfAStreamOfOddSize) {
  const Scene scene = loadScene("cornell");
  GpuTraversalConfig config;
  config.loopLimit = 3;
  const auto traversal = makeStreamStructure("kk-bvh", scene.triangles, config);
  ShadingConfig shading;
  shading.mode = ShadingMode::Whitted;
  GpuRenderer off(scene, *traversal, 30, 19, 0, shading, Compaction::Off);
  GpuRenderer on(scene, *traversal, 30, 19, 0, shading, Compaction::On);
  const FrameResult a = off.render(scene.camera, 3, false), b = on.render(scene.camera, 3, false);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.stats.triangleTests, b.stats.triangleTests);
}

INSTANTIATE_TEST_SUITE_P(EveryStreamRow, CompactOnOff,
                         ::testing::ValuesIn(testing_registry::rowNames(RendererId::Gpu)),
                         testing_registry::CaseNameOfRow());

}  // namespace
}  // namespace passtrace
