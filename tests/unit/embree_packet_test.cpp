// Embree's packet path (rtcIntersect16/8/4, rtcOccluded16/8/4 through
// CpuAccelerator::tracePacket): the same hits as its per-ray path bit for bit,
// in packets of every fill (masked-off lanes, rays that cannot hit), and
// through the CPU renderer the same image and primary hits as the per-ray
// path and as brute force but for Embree's own rounding of t.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "accel/cpu_accelerator.h"
#include "accel/embree/embree_accelerator.h"
#include "render/cpu_renderer.h"
#include "scenes/scene_registry.h"
#include "tests/hit_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

// The accelerator with its packet interface hidden: the renderer traces it ray by ray.
class PerRayOnly final : public CpuAccelerator {
 public:
  explicit PerRayOnly(const CpuAccelerator& inner) : inner_(inner) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return inner_.intersect(ray, anyHit, stats);
  }
  std::string name() const override { return inner_.name(); }
  AccelStats stats() const override { return inner_.stats(); }

 private:
  const CpuAccelerator& inner_;
};

bool sameOrBothNaN(const Hit& a, const Hit& b) {
  if (std::isnan(a.t) || std::isnan(b.t)) return std::isnan(a.t) && std::isnan(b.t) && a.id == b.id;
  return test::sameHit(a, b);
}

class EmbreePacket : public ::testing::TestWithParam<testmesh::NamedMesh> {
 protected:
  void SetUp() override {
    if (!PASSTRACE_HAVE_EMBREE) GTEST_SKIP() << "passtrace was built without Embree";
  }
};

TEST_P(EmbreePacket, PacketsOfEveryFillEqualSingleRays) {
  const auto& tris = GetParam().tris;
  const auto accel = makeEmbreeAccelerator(tris);
  const size_t width = size_t(accel->packetSize());
  ASSERT_GT(width, 0u) << "Embree built without ray packets";
  std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 100, 11);
  // Rays that can hit nothing take masked-off lanes among live ones.
  const float dead[] = {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
  for (size_t i = 5; i < rays.size(); i += 7) rays[i].tMax = dead[i % 3];
  size_t hits = 0, occluded = 0;
  for (const size_t n : {size_t(1), size_t(3), width - 1, width, width + 1, 2 * width + 5}) {
    for (const bool anyHit : {false, true}) {
      size_t wrong = 0;
      for (size_t first = 0; first < rays.size(); first += n) {
        const size_t m = std::min(n, rays.size() - first);
        std::vector<Hit> got(m);
        std::vector<RayStats> stats(m);
        accel->tracePacket(RayPacket::of(std::span<const Ray>(rays).subspan(first, m)), anyHit, got, stats);
        for (size_t k = 0; k < m; ++k) {
          const Hit want = accel->intersect(rays[first + k], anyHit, nullptr);
          wrong += !sameOrBothNaN(got[k], want);
          hits += !anyHit && want.found();
          occluded += anyHit && want.found();
          EXPECT_EQ(stats[k].steps + stats[k].triangleTests, 0u) << "Embree counts nothing";
        }
      }
      EXPECT_EQ(wrong, 0u) << GetParam().name << ": packets of " << n << (anyHit ? ", any hit" : ", closest hit");
    }
  }
  EXPECT_GT(hits, 0u);
  EXPECT_GT(occluded, 0u);
}

INSTANTIATE_TEST_SUITE_P(Meshes, EmbreePacket, ::testing::ValuesIn(testmesh::standardMeshes()),
                         [](const auto& info) { return info.param.name; });

struct Case {
  std::string scene;
  int width, height, bounces;
};

class EmbreePacketRenderer : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    if (!PASSTRACE_HAVE_EMBREE) GTEST_SKIP() << "passtrace was built without Embree";
  }
};

TEST_P(EmbreePacketRenderer, ImagesEqualPerRayAndBruteForce) {
  const Case c = GetParam();
  SceneOptions options;
  options.triangles = 3000;  // spheres: small enough for brute force
  const Scene scene = loadScene(c.scene, options);
  const auto embree = makeEmbreeAccelerator(scene.triangles);
  ASSERT_GT(embree->packetSize(), 0) << "the renderer takes the packet path";
  const PerRayOnly perRay(*embree);
  const auto brute = makeBruteForceAccelerator(scene.triangles);
  const FrameResult got = CpuRenderer(scene, *embree, 2).render(scene.camera, c.width, c.height, c.bounces, true);
  const FrameResult single = CpuRenderer(scene, perRay, 2).render(scene.camera, c.width, c.height, c.bounces, true);
  const FrameResult want = CpuRenderer(scene, *brute, 2).render(scene.camera, c.width, c.height, c.bounces, true);
  ASSERT_EQ(got.rgb.size(), want.rgb.size());
  ASSERT_EQ(got.primaryHits.size(), want.primaryHits.size());
  EXPECT_EQ(got.stats.rays, single.stats.rays);
  EXPECT_TRUE(got.rgb == single.rgb) << "packets and single rays: bit-identical images";
  size_t hitDiffer = 0, hitMissDiffer = 0, differ = 0;
  for (size_t p = 0; p < got.primaryHits.size(); ++p) {
    const HitRecord& a = got.primaryHits[p];
    const HitRecord& b = single.primaryHits[p];
    hitDiffer += a.t != b.t || a.id != b.id || a.u != b.u || a.v != b.v;
    // Brute force: the same hit or miss; t within Embree's rounding (see embree_accelerator.h).
    const HitRecord& w = want.primaryHits[p];
    hitMissDiffer += (a.id == kNoHit) != (w.id == kNoHit) || (a.id != kNoHit && !test::tiedT(a.t, w.t, 1e-4f));
    bool same = true;
    for (int k = 0; k < 3; ++k) same = same && std::abs(got.rgb[3 * p + k] - want.rgb[3 * p + k]) <= 1e-4f;
    differ += !same;
  }
  EXPECT_EQ(hitDiffer, 0u) << "primary hits: packets against single rays";
  EXPECT_EQ(hitMissDiffer, 0u) << "primary hits against brute force";
  // Shadow rays that graze an edge may decide differently from Möller–Trumbore's.
  EXPECT_LE(differ, got.primaryHits.size() / 200) << differ << " pixels differ from brute force";
}

INSTANTIATE_TEST_SUITE_P(Scenes, EmbreePacketRenderer,
                         ::testing::Values(Case{"cornell", 61, 45, 3}, Case{"spheres", 70, 37, 2}),
                         [](const auto& info) { return info.param.scene; });

}  // namespace
}  // namespace passtrace
