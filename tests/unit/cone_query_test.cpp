// Cone queries (accel/cone/): the exact cone/triangle test against sampled
// points and hand-made cases, the cone/box interval against sampled points,
// and the kd-tree and BVH traversals against the brute-force query.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "accel/cone/cone_tests.h"
#include "accel/cone/cone_traversal.h"
#include "accel/registry.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using namespace testmesh;

float radians(float degrees) { return degrees * float(std::numbers::pi) / 180.0f; }

bool insideCone(const Cone& cone, const glm::vec3& p, float& t) {
  const glm::dvec3 d = glm::dvec3(p) - glm::dvec3(cone.apex);
  t = float(glm::dot(d, glm::dvec3(cone.axis)));
  return t >= 0.0f && double(t) >= glm::length(d) * std::cos(double(cone.halfAngle));
}

TEST(ConeTriangle, AxisThroughTheTriangleMeetsItAtTheCrossing) {
  const Triangle tri{{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}};
  float t = 0;
  ASSERT_TRUE(coneMeetsTriangle(Cone{{0, 0, 0}, {0, 0, 1}, 0.0f}, tri, t));
  EXPECT_FLOAT_EQ(t, 5.0f);
  EXPECT_FALSE(coneMeetsTriangle(Cone{{0, 0, 0}, {0, 0, -1}, radians(30)}, tri, t));  // behind the apex
}

TEST(ConeTriangle, ATriangleBesideTheAxisIsMetFromItsAngleOn) {
  // The nearest point (0, 1, 10) is atan(0.1) = 5.71 degrees off the axis.
  const Triangle tri{{-1, 1, 10}, {1, 1, 10}, {0, 3, 10}};
  float t = 0;
  EXPECT_FALSE(coneMeetsTriangle(Cone{{0, 0, 0}, {0, 0, 1}, radians(5.6f)}, tri, t));
  ASSERT_TRUE(coneMeetsTriangle(Cone{{0, 0, 0}, {0, 0, 1}, radians(5.8f)}, tri, t));
  EXPECT_NEAR(t, 10.0f, 1e-4f);
}

TEST(ConeTriangle, TheNearestPointMayLieInsideTheTriangle) {
  // A plane z = 10 + y tan(30 deg) cut by a 10-degree cone about +z: the
  // section is an ellipse inside the triangle; its nearest point lies on
  // the generator (0, -sin a, cos a), at t = 10 cos a / (cos a + sin a tan 30).
  const float tan30 = std::tan(radians(30));
  const Triangle tri{{-50, -20, 10 - 20 * tan30}, {50, -20, 10 - 20 * tan30}, {0, 40, 10 + 40 * tan30}};
  const float a = radians(10);
  float t = 0;
  ASSERT_TRUE(coneMeetsTriangle(Cone{{0, 0, 0}, {0, 0, 1}, a}, tri, t));
  EXPECT_NEAR(t, 10 * std::cos(a) / (std::cos(a) + std::sin(a) * tan30), 1e-4f);
}

TEST(ConeTriangle, AgreesWithSampledPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
  int met = 0, missed = 0;
  for (int c = 0; c < 400; ++c) {
    const Triangle tri{{u(rng), u(rng), 3 + u(rng)}, {u(rng), u(rng), 3 + u(rng)}, {u(rng), u(rng), 3 + u(rng)}};
    const glm::vec3 axis = glm::normalize(glm::vec3(0.3f * u(rng), 0.3f * u(rng), 1.0f));
    const Cone cone{{0.2f * u(rng), 0.2f * u(rng), 0.0f}, axis, radians(20.0f * w(rng))};
    float t = 0;
    const bool meets = coneMeetsTriangle(cone, tri, t);
    (meets ? met : missed) += 1;
    // Any sampled point inside the cone means the test says it meets, and
    // its t is the nearest point's (no sample is nearer).
    float nearestSample = kInfinity;
    for (int s = 0; s < 2000; ++s) {
      float a = w(rng), b = w(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      float ts;
      if (insideCone(cone, tri.v0 + a * (tri.v1 - tri.v0) + b * (tri.v2 - tri.v0), ts))
        nearestSample = std::min(nearestSample, ts);
    }
    if (nearestSample < kInfinity) {
      ASSERT_TRUE(meets) << "cone " << c;
      EXPECT_LE(t, nearestSample * (1 + 1e-5f) + 1e-5f) << "cone " << c;
    }
  }
  EXPECT_GT(met, 50);
  EXPECT_GT(missed, 50);
}

TEST(ConeBox, TheIntervalHoldsEverySampledPointOfTheBoxInsideTheCone) {
  // Apexes inside and outside the slabs, axes pointing towards and away
  // from the box: Figure 5's cases (the digest's sign bug loses some).
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
  const Aabb box{{-1, -0.5f, 2}, {1, 0.5f, 3}};
  int tested = 0;
  for (int c = 0; c < 300; ++c) {
    const Cone cone{{2 * u(rng), 2 * u(rng), 2.5f + 2 * u(rng)}, glm::normalize(glm::vec3(u(rng), u(rng), u(rng))),
                    radians(30.0f * w(rng))};
    float t0 = 0, t1 = kInfinity;
    const bool open = coneBox(cone, coneSpread(cone), box, t0, t1);
    for (int s = 0; s < 2000; ++s) {
      const glm::vec3 p = box.min + glm::vec3(w(rng), w(rng), w(rng)) * box.extent();
      float t;
      if (!insideCone(cone, p, t)) continue;
      ++tested;
      ASSERT_TRUE(open) << "cone " << c;
      EXPECT_GE(t, t0 * (1 - 1e-4f) - 1e-4f) << "cone " << c;
      EXPECT_LE(t, t1 * (1 + 1e-4f) + 1e-4f) << "cone " << c;
    }
  }
  EXPECT_GT(tested, 1000);
}

class ConeTraversals : public ::testing::TestWithParam<NamedMesh> {};

// Every row with a cone query returns exactly the brute-force list: the
// same triangles, the same t, in the same order, with and without a cap.
TEST_P(ConeTraversals, MatchBruteForce) {
  const std::vector<Triangle>& tris = GetParam().tris;
  const Aabb bounds = boundsOf(tris);
  const auto brute = makeBruteForceCone(tris);
  std::vector<std::unique_ptr<ConeTraversal>> rows;
  for (const Structure& s : structures())
    if (s.cone) rows.push_back(s.cone(tris, AccelBuildConfig{}));
  ASSERT_GE(rows.size(), 2u);
  ConeScratch scratch;
  ConeResult expected, got;
  size_t nonEmpty = 0;
  const std::vector<Ray> rays = rayMix(bounds, 12, 3);
  for (float degrees : {0.0f, 0.04f, 0.5f, 2.5f, 30.0f})
    for (uint32_t maxHits : {0u, 4u})
      for (size_t i = 0; i < rays.size(); ++i) {
        const Cone cone{rays[i].origin, glm::normalize(rays[i].direction), radians(degrees)};
        const ConeQueryConfig config{maxHits};
        brute->query(cone, config, scratch, expected);
        nonEmpty += !expected.hits.empty();
        for (const auto& row : rows)
          for (bool sorted : {false, true}) {
            ConeQueryConfig variant = config;
            variant.sortedNodes = sorted;
            row->query(cone, variant, scratch, got);
            ASSERT_EQ(got.hits.size(), expected.hits.size())
                << row->stats().name << " " << degrees << " deg ray " << i << " max " << maxHits << " sorted "
                << sorted;
            for (size_t h = 0; h < got.hits.size(); ++h) {
              EXPECT_EQ(got.hits[h].id, expected.hits[h].id) << row->stats().name << " ray " << i << " hit " << h;
              EXPECT_EQ(got.hits[h].t, expected.hits[h].t) << row->stats().name << " ray " << i << " hit " << h;
            }
          }
      }
  if (tris.size() > 1) {
    EXPECT_GT(nonEmpty, 0u);
  }
}

// A cone of 0 degrees is the ray: it meets whatever the ray hits, never
// farther (an edge grazed exactly may count as met where the ray test
// rounds it away).
TEST_P(ConeTraversals, ZeroAngleIsTheRay) {
  const std::vector<Triangle>& tris = GetParam().tris;
  const auto kd = makeKdTreeCone(tris, {});
  ConeScratch scratch;
  ConeResult got;
  for (const Ray& ray : rayMix(boundsOf(tris), 12, 5)) {
    const glm::vec3 dir = glm::normalize(ray.direction);
    Hit hit;
    for (uint32_t id = 0; id < tris.size(); ++id) intersectTriangle(ray.origin, dir, tris[id], id, hit);
    kd->query(Cone{ray.origin, dir, 0.0f}, {}, scratch, got);
    if (hit.found()) {
      ASSERT_FALSE(got.hits.empty());
      EXPECT_LE(got.hits.front().t, hit.t + 1e-4f * std::max(1.0f, hit.t));
    }
  }
}

// Resuming (seed 000 section 3): the n nearest, then the next n from just
// past the last one's t, make the 2n nearest (when no tie straddles the cut).
TEST(ConeResume, TNearContinuesTheList) {
  const std::vector<Triangle> tris = uvSphere(16, 24);
  ConeScratch scratch;
  ConeResult all, first, second;
  size_t resumed = 0;
  for (const Structure& s : structures()) {
    if (!s.cone) continue;
    const auto row = s.cone(tris, {});
    for (const Ray& ray : rayMix(boundsOf(tris), 8, 9)) {
      const Cone cone{ray.origin, glm::normalize(ray.direction), radians(20)};
      row->query(cone, {}, scratch, all);
      row->query(cone, {3}, scratch, first);
      if (first.hits.size() < 3) continue;
      const float next = std::nextafter(first.hits.back().t, kInfinity);
      if (all.hits.size() > 3 && all.hits[3].t == first.hits.back().t) continue;  // a tie at the cut
      row->query(cone, {3, next}, scratch, second);
      for (size_t i = 0; i < 6 && i < all.hits.size(); ++i) {
        const ConeHit& h = i < 3 ? first.hits[i] : second.hits[i - 3];
        EXPECT_EQ(h.id, all.hits[i].id) << s.name << " hit " << i;
      }
      ++resumed;
    }
  }
  EXPECT_GT(resumed, 10u);
}

INSTANTIATE_TEST_SUITE_P(Meshes, ConeTraversals, ::testing::ValuesIn(standardMeshes()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace passtrace
