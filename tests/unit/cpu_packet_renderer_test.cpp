// The CPU renderer's packet path (bvh8-packet, binned and --bvh8-builder sbvh builds: 8x8 tiles, closest-hit packets
// of 32 and shadow packets of up to 64 read straight from the paths) against
// brute force on whole images with shadow rays: the same colour in every pixel
// but for a few ties in t; and its packets taking turns, eight tiles at once. Image sizes that are not multiples of 8 give the
// tiles at the right and bottom edges fewer rays.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "accel/cpu_accelerator.h"
#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_structure.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "render/cpu_renderer.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

struct Case {
  std::string scene;
  int width, height, bounces;
  Bvh8BuilderKind builder = Bvh8BuilderKind::Binned;
};

// Renders with `tracer` and with brute force: the same colour in every pixel
// but for ties, and the same primary hit distances.
void expectImagesEqualBruteForce(const Scene& scene, const CpuAccelerator& tracer, const Case& c) {
  const auto brute = makeBruteForceAccelerator(scene.triangles);
  const FrameResult got = CpuRenderer(scene, tracer, 2).render(scene.camera, c.width, c.height, c.bounces, true);
  const FrameResult want = CpuRenderer(scene, *brute, 2).render(scene.camera, c.width, c.height, c.bounces, true);
  ASSERT_EQ(got.rgb.size(), want.rgb.size());
  ASSERT_EQ(got.stats.rays, want.stats.rays) << "the same shadow rays were spawned and traced";
  size_t differ = 0, hitDiffer = 0;
  for (size_t p = 0; p < got.primaryHits.size(); ++p) {
    bool same = true;
    for (int k = 0; k < 3; ++k) same = same && std::abs(got.rgb[3 * p + k] - want.rgb[3 * p + k]) <= 1e-5f;
    differ += !same;
    hitDiffer += got.primaryHits[p].t != want.primaryHits[p].t;
  }
  EXPECT_EQ(hitDiffer, 0u) << "primary hit distances";
  // Ties between triangles at the same t may shade differently (another normal).
  EXPECT_LE(differ, got.primaryHits.size() / 200) << differ << " pixels differ";
}

Scene testScene(const std::string& name) {
  SceneOptions options;
  options.triangles = 3000;  // spheres: small enough for brute force
  return loadScene(name, options);
}

class CpuPacketRenderer : public ::testing::TestWithParam<Case> {};

TEST_P(CpuPacketRenderer, ImagesEqualBruteForceButForTies) {
  if (!wideBvhAvx2Available()) GTEST_SKIP() << "no AVX2: bvh8-packet takes the per-ray path";
  const Case c = GetParam();
  const Scene scene = testScene(c.scene);
  AccelBuildConfig config;
  config.bvh8Builder = c.builder;
  const auto packets = makeBvh8PacketCpu(scene.triangles, config);
  ASSERT_GT(packets->packetSize(), 32) << "shadow packets of up to 64 rays";
  expectImagesEqualBruteForce(scene, *packets, c);
}

// bvh8-packet's traversal as it runs over trees larger than
// kTakeTurnsAboveBytes, whatever the tree's size: the renderer hands over
// eight tiles' packets at once and they take turns.
class TurnTakingPackets final : public CpuAccelerator {
public:
  explicit TurnTakingPackets(std::span<const Triangle> tris)
      : tris_(tris), bvh_(collapseToWideBvh(buildBinnedSahBvh(tris), tris)) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseWideBvhAvx2(bvh_, tris_, ray, anyHit, TriangleTest::MollerTrumbore, stats);
  }
  int packetSize() const override { return kWidePacketMax; }
  void tracePacket(const RayPacket& rays, bool anyHit, std::span<Hit> hits, std::span<RayStats> stats) const override {
    traceWideBvhPacketAvx2(bvh_, rays, anyHit, hits, stats, packetConfigFor(anyHit));
  }
  int packetsAtOnce() const override { return 8; }
  void tracePackets(std::span<const PacketJob> jobs, bool anyHit) const override {
    traceWideBvhPacketsAvx2(bvh_, jobs, anyHit, packetConfigFor(anyHit), true);
  }
  std::string name() const override { return "bvh8-packet, taking turns"; }
  AccelStats stats() const override { return {}; }

private:
  std::span<const Triangle> tris_;
  WideBvh bvh_;
};

TEST_P(CpuPacketRenderer, PacketsTakingTurnsEqualBruteForceButForTies) {
  if (!wideBvhAvx2Available()) GTEST_SKIP() << "no AVX2: bvh8-packet takes the per-ray path";
  const Case c = GetParam();
  const Scene scene = testScene(c.scene);
  const TurnTakingPackets packets(scene.triangles);
  expectImagesEqualBruteForce(scene, packets, c);
  expectImagesEqualBruteForce(scene, packets, Case{c.scene, c.width, c.height, 1});  // the primary-only frame
}

INSTANTIATE_TEST_SUITE_P(Scenes, CpuPacketRenderer,
                         ::testing::Values(Case{"cornell", 61, 45, 3}, Case{"spheres", 70, 37, 2},
                                           Case{"cornell", 61, 45, 3, Bvh8BuilderKind::Sbvh},
                                           Case{"spheres", 70, 37, 2, Bvh8BuilderKind::Sbvh}),
                         [](const auto& info) {
                           return info.param.scene + (info.param.builder == Bvh8BuilderKind::Sbvh ? "_sbvh" : "");
                         });

}  // namespace
}  // namespace passtrace
