// -r 2 --stage compute (stream/stream_stage.h): every stream row of the
// registry renders in the compute stage what it renders in the fragment
// stage, bit for bit (image, per-pixel steps, counts, passes and primary
// hits), with the per-pass schedule (-l), compaction and the shading mixes;
// and its primary hits are brute force's (ties aside); also where its
// streams store through image units.

#include <gtest/gtest.h>

#include <ostream>

#include "accel/brute_force.h"
#include "accel/registry.h"
#include "render/camera.h"
#include "render/gpu_renderer.h"
#include "scenes/scene_registry.h"
#include "stream/inout_stream.h"
#include "tests/frame_checks.h"
#include "tests/gl_test_support.h"
#include "tests/hit_checks.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

struct Settings {
  const char* scene;
  ShadingMode shading;
  int bounces;
  int loopLimit;  // 0: one pass per bounce
  Compaction compact;
};

FrameResult render(const Scene& scene, const std::string& row, const Settings& s, StreamStage stage) {
  const StreamStageScope scope(stage);
  GpuTraversalConfig config;
  config.loopLimit = s.loopLimit;
  config.compact = s.compact;
  config = withPassStepLimit(config);
  const auto structure = makeStreamStructure(row, scene.triangles, config);
  ShadingConfig shading;
  shading.mode = s.shading;
  shading.aoSamples = 2;
  GpuRenderer renderer(scene, *structure, 29, 23, 0, shading, s.compact);  // sides not multiples of a tile's
  return renderer.render(scene.camera, s.bounces, /*captureHits=*/true);
}

class ComputeStage : public test::GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(ComputeStage, RendersWhatTheFragmentStageRenders) {
  const Settings settings[] = {
      {"cornell", ShadingMode::Thesis, 3, 0, Compaction::Off},     // primary, shadow and mirror rays
      {"cornell", ShadingMode::Thesis, 2, 3, Compaction::Always},  // resumed passes, gathered rays
      {"cornell", ShadingMode::Whitted, 3, 0, Compaction::On},
      {"bunny", ShadingMode::Ao, 2, 0, Compaction::Off},
  };
  for (const Settings& s : settings) {
    SCOPED_TRACE(std::string(s.scene) + " " + shadingModeName(s.shading) + " -b " + std::to_string(s.bounces) +
                 " -l " + std::to_string(s.loopLimit) + " --compact " + compactionName(s.compact));
    const Scene scene = loadScene(s.scene);
    const FrameResult compute = render(scene, GetParam(), s, StreamStage::Compute);
    const FrameResult fragment = render(scene, GetParam(), s, StreamStage::Fragment);
    EXPECT_GT(compute.stats.steps, 0u);
    test::expectSameFrame(compute, fragment);

    // The primary hits against brute force over the camera's rays.
    const CameraBasis basis = makeCameraBasis(scene.camera, compute.width, compute.height);
    ASSERT_EQ(compute.primaryHits.size(), size_t(compute.width) * size_t(compute.height));
    int hits = 0;
    for (int y = 0; y < compute.height; ++y)
      for (int x = 0; x < compute.width; ++x) {
        const Hit want = intersectBruteForce(scene.triangles, primaryRay(basis, x, y), false);
        const HitRecord got = compute.primaryHits[size_t(y) * size_t(compute.width) + size_t(x)];
        ASSERT_EQ(got.id == kNoHit, want.id == kNoHit) << "pixel " << x << "," << y;
        if (want.id == kNoHit) continue;
        ++hits;
        ASSERT_TRUE(got.id == want.id || test::tiedT(got.t, want.t)) << "pixel " << x << "," << y;
      }
    EXPECT_GT(hits, compute.width * compute.height / 8);  // the bunny covers about a sixth of its view
  }
}

// Streams larger than the driver's largest storage block store through image
// units instead (stream/inout_stream.h); forced here on small ones: resumed
// passes and compaction, which reads and writes every surface.
TEST_P(ComputeStage, ThroughImageUnitsRendersWhatTheFragmentStageRenders) {
  struct Limit {
    Limit() { InOutStream::limitStorageBlock(1); }
    ~Limit() { InOutStream::limitStorageBlock(0); }
  };
  const Settings s{"cornell", ShadingMode::Thesis, 2, 3, Compaction::Always};
  const Scene scene = loadScene(s.scene);
  const FrameResult fragment = render(scene, GetParam(), s, StreamStage::Fragment);
  const Limit limit;
  const FrameResult compute = render(scene, GetParam(), s, StreamStage::Compute);
  EXPECT_GT(compute.stats.steps, 0u);
  test::expectSameFrame(compute, fragment);
}

INSTANTIATE_TEST_SUITE_P(EveryStreamRow, ComputeStage,
                         ::testing::ValuesIn(testing_registry::rowNames(RendererId::Gpu)),
                         testing_registry::CaseNameOfRow{});

}  // namespace
}  // namespace passtrace
