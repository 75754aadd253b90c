// Embree (the CPU baseline): agreement with brute force on the standard
// meshes, any-hit with finite tMax, the strict tMax rule, thread safety, the
// empty scene and AccelStats. Embree's triangle test is not passtrace's
// Möller–Trumbore, so closest hits may differ only in which of several
// triangles at the same t wins (a t tie within 1e-6 relative).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/embree/embree_accelerator.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"
#include "tests/hit_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using testmesh::NamedMesh;

using test::sameHit;
using test::tiedT;

// What an occluded any-hit query returns (see embree_accelerator.h).
constexpr Hit kOccluded{0.0f, 0.0f, 0.0f, 0u};

struct Agreement {
  size_t queries = 0, hits = 0, anyHits = 0, finiteTMaxAnyHitQueries = 0, finiteTMaxAnyHits = 0;
  size_t foundMismatch = 0, tieMismatch = 0, anyFoundMismatch = 0, badAnyHitValue = 0, idDiffersButTied = 0;
  float maxRelTDiff = 0, maxUvDiff = 0;  // between Embree and MT on the same triangle
  std::vector<std::string> examples;     // the first few mismatches, for the failure message
};

std::string describe(const Ray& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) tMax=%.9g", r.origin.x, r.origin.y,
                r.origin.z, r.direction.x, r.direction.y, r.direction.z, r.tMax);
  return buf;
}

Agreement compare(const CpuAccelerator& accel, std::span<const Triangle> tris, std::span<const Ray> rays) {
  Agreement a;
  for (const Ray& ray : rays) {
    ++a.queries;
    RayStats stats;
    const Hit h = accel.intersect(ray, false, &stats);
    EXPECT_EQ(stats.steps, 0u);  // Embree reports nothing; stats stay untouched
    EXPECT_EQ(stats.triangleTests, 0u);
    const Hit b = intersectBruteForce(tris, ray, false);
    if (h.found() != b.found()) {
      ++a.foundMismatch;
      if (a.examples.size() < 5)
        a.examples.push_back("closest " + describe(ray) + ": embree " + (h.found() ? "hit " : "miss ") +
                             std::to_string(h.id) + " t=" + std::to_string(h.t) + ", brute force " +
                             (b.found() ? "hit " : "miss ") + std::to_string(b.id) + " t=" + std::to_string(b.t));
    } else if (h.found()) {
      ++a.hits;
      EXPECT_LT(h.t, ray.tMax);
      EXPECT_GT(h.t, 0.0f);
      if (h.id == b.id) {
        a.maxRelTDiff = std::max(a.maxRelTDiff, std::fabs(h.t - b.t) / std::max(std::fabs(b.t), 1e-30f));
        a.maxUvDiff = std::max({a.maxUvDiff, std::fabs(h.u - b.u), std::fabs(h.v - b.v)});
      } else if (tiedT(h.t, b.t)) {
        ++a.idDiffersButTied;
      } else {
        ++a.tieMismatch;
        if (a.examples.size() < 5)
          a.examples.push_back("closest " + describe(ray) + ": embree " + std::to_string(h.id) + " t=" +
                               std::to_string(h.t) + ", brute force " + std::to_string(b.id) +
                               " t=" + std::to_string(b.t));
      }
    } else {
      EXPECT_EQ(h.t, ray.tMax);
    }

    const bool finite = std::isfinite(ray.tMax);
    a.finiteTMaxAnyHitQueries += finite;
    const Hit ha = accel.intersect(ray, true, nullptr);
    const Hit ba = intersectBruteForce(tris, ray, true);
    if (ha.found() != ba.found()) {
      ++a.anyFoundMismatch;
      if (a.examples.size() < 5)
        a.examples.push_back("any " + describe(ray) + ": embree " + (ha.found() ? "occluded" : "clear") +
                             ", brute force " + (ba.found() ? "hit " + std::to_string(ba.id) : "miss"));
    }
    if (ha.found()) {
      ++a.anyHits;
      a.finiteTMaxAnyHits += finite;
      a.badAnyHitValue += !sameHit(ha, kOccluded);
    } else {
      a.badAnyHitValue += !(ha.t == ray.tMax || (std::isnan(ha.t) && std::isnan(ray.tMax)));
    }
  }
  return a;
}

// Built without Embree (PASSTRACE_HAVE_EMBREE 0) makeEmbreeAccelerator()
// throws: every test here is skipped.
class EmbreeMeshTest : public ::testing::TestWithParam<NamedMesh> {
 protected:
  void SetUp() override {
    if (!PASSTRACE_HAVE_EMBREE) GTEST_SKIP() << "passtrace was built without Embree";
  }
};

class Embree : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!PASSTRACE_HAVE_EMBREE) GTEST_SKIP() << "passtrace was built without Embree";
  }
};

TEST_P(EmbreeMeshTest, AgreesWithBruteForce) {
  const auto& tris = GetParam().tris;
  const auto accel = makeEmbreeAccelerator(tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 1000, 42);
  const Agreement a = compare(*accel, tris, rays);
  std::string examples;
  for (const auto& e : a.examples) examples += "\n  " + e;
  const std::string& what = GetParam().name;
  EXPECT_EQ(a.foundMismatch, 0u) << what << examples;
  EXPECT_EQ(a.tieMismatch, 0u) << what << examples;
  EXPECT_EQ(a.anyFoundMismatch, 0u) << what << examples;
  EXPECT_EQ(a.badAnyHitValue, 0u) << what;
  EXPECT_GT(a.hits, 0u) << what;
  EXPECT_GT(a.finiteTMaxAnyHits, 0u) << what << ": no any-hit query with finite tMax hit";
  // Same triangle: Embree's t and barycentrics are close to MT's; at grazing
  // angles t is ill-conditioned, so the two formulas differ by up to ~1e-3
  // relative there (seen on the soup and coincident meshes).
  EXPECT_LT(a.maxRelTDiff, 1e-2f) << what;
  EXPECT_LT(a.maxUvDiff, 1e-2f) << what;
}

// Many threads over one accelerator give exactly the sequential answers.
TEST_P(EmbreeMeshTest, ThreadsGiveTheSequentialResults) {
  const auto& tris = GetParam().tris;
  const auto accel = makeEmbreeAccelerator(tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 500, 77);
  std::vector<Hit> closest(rays.size()), any(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    closest[i] = accel->intersect(rays[i], false, nullptr);
    any[i] = accel->intersect(rays[i], true, nullptr);
  }
  constexpr int kThreads = 8;
  std::vector<size_t> wrong(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      // Each thread walks the rays from a different start, several times.
      for (int pass = 0; pass < 3; ++pass)
        for (size_t k = 0; k < rays.size(); ++k) {
          const size_t i = (k + size_t(t) * rays.size() / kThreads) % rays.size();
          RayStats stats;
          wrong[t] += !sameHit(accel->intersect(rays[i], false, &stats), closest[i]);
          wrong[t] += !sameHit(accel->intersect(rays[i], true, &stats), any[i]);
        }
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(wrong[t], 0u) << GetParam().name << " thread " << t;
}

std::string meshName(const ::testing::TestParamInfo<NamedMesh>& info) { return info.param.name; }
INSTANTIATE_TEST_SUITE_P(Meshes, EmbreeMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()), meshName);

TEST_F(Embree, EmptySceneHitsNothing) {
  const std::vector<Triangle> none;
  const auto accel = makeEmbreeAccelerator(none);
  const std::vector<Ray> rays = testmesh::rayMix(Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)}, 50, 5);
  for (const Ray& ray : rays)
    for (const bool anyHit : {false, true}) {
      const Hit h = accel->intersect(ray, anyHit, nullptr);
      EXPECT_FALSE(h.found());
      EXPECT_EQ(h.t, ray.tMax);
    }
  const AccelStats s = accel->stats();
  EXPECT_EQ(s.name, "embree");
  EXPECT_EQ(s.references, 0u);
}

TEST_F(Embree, Stats) {
  const std::vector<Triangle> tris = testmesh::uvSphere(16, 24);
  const auto accel = makeEmbreeAccelerator(tris);
  EXPECT_EQ(accel->name(), "embree");
  const AccelStats s = accel->stats();
  EXPECT_EQ(s.name, "embree");
  EXPECT_GT(s.buildMs, 0.0);
  EXPECT_LT(s.buildMs, 60000.0);
  EXPECT_EQ(s.floatsPerTriangle, 0.0);  // not reported by Embree
  EXPECT_EQ(s.nodes, 0u);
  EXPECT_EQ(s.leaves, 0u);
  EXPECT_EQ(s.depth, 0u);
  EXPECT_EQ(s.references, tris.size());
}

// Passtrace's rule is 0 < t < tMax; Embree on its own accepts t == tfar.
TEST_F(Embree, TMaxIsExclusiveAndNonPositiveTMaxMisses) {
  const std::vector<Triangle> tris = testmesh::singleTriangle();
  const auto accel = makeEmbreeAccelerator(tris);
  Ray ray{glm::vec3(-0.5f, -0.5f, 1.0f), glm::vec3(0.0f, 0.0f, -1.0f), kInfinity};
  const Hit h = accel->intersect(ray, false, nullptr);
  ASSERT_TRUE(h.found());
  // Embree divides with an approximate reciprocal: t may be off by an ulp.
  EXPECT_TRUE(tiedT(h.t, 1.0f)) << h.t;
  EXPECT_EQ(h.id, 0u);
  // u, v weight the second and third vertex: (-0.5,-0.5) = 0.5 v0 + 0.25 v1 + 0.25 v2.
  EXPECT_NEAR(h.u, 0.25f, 1e-6f);
  EXPECT_NEAR(h.v, 0.25f, 1e-6f);
  EXPECT_EQ(intersectBruteForce(tris, ray, false).t, 1.0f);

  for (const bool anyHit : {false, true}) {
    ray.tMax = 1.0f;  // the hit is exactly at tMax: excluded
    EXPECT_FALSE(accel->intersect(ray, anyHit, nullptr).found()) << anyHit;
    EXPECT_FALSE(intersectBruteForce(tris, ray, anyHit).found());
    ray.tMax = std::nextafter(1.0f, 2.0f);  // just beyond: included
    EXPECT_TRUE(accel->intersect(ray, anyHit, nullptr).found()) << anyHit;
    EXPECT_TRUE(intersectBruteForce(tris, ray, anyHit).found());
    for (const float tMax : {0.0f, -1.0f, -kInfinity, std::nanf("")}) {
      ray.tMax = tMax;
      EXPECT_FALSE(accel->intersect(ray, anyHit, nullptr).found()) << tMax;
    }
  }
  // The origin on the triangle (t = 0) is not a hit.
  const Ray onPlane{glm::vec3(-0.5f, -0.5f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f), kInfinity};
  EXPECT_FALSE(accel->intersect(onPlane, false, nullptr).found());
  EXPECT_FALSE(intersectBruteForce(tris, onPlane, false).found());
}

TEST_F(Embree, DegenerateInputDoesNotCrash) {
  const std::vector<Triangle> points = testmesh::pointMesh(10);
  const auto accel = makeEmbreeAccelerator(points);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(points), 50, 9);
  for (const Ray& ray : rays)
    for (const bool anyHit : {false, true}) EXPECT_FALSE(accel->intersect(ray, anyHit, nullptr).found());
  // A zero direction, and rays with zero components, against a real mesh.
  const std::vector<Triangle> sphere = testmesh::uvSphere(8, 8);
  const auto s = makeEmbreeAccelerator(sphere);
  EXPECT_FALSE(s->intersect(Ray{glm::vec3(0.0f), glm::vec3(0.0f), kInfinity}, false, nullptr).found());
  EXPECT_FALSE(s->intersect(Ray{glm::vec3(0.0f), glm::vec3(0.0f), kInfinity}, true, nullptr).found());
  const Hit h = s->intersect(Ray{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), kInfinity}, false, nullptr);
  EXPECT_TRUE(h.found());
}

// The Stanford bunny, when glmark2-data is installed: a spot check against
// brute force.
TEST_F(Embree, BunnyAgreesWithBruteForce) {
  Scene scene;
  try {
    scene = loadScene("bunny");
  } catch (const SceneError& e) {
    GTEST_SKIP() << e.what();
  }
  const std::vector<Triangle>& tris = scene.triangles;
  ASSERT_FALSE(tris.empty());
  const auto accel = makeEmbreeAccelerator(tris);
  const AccelStats s = accel->stats();
  EXPECT_EQ(s.references, tris.size());
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 50, 21);
  const Agreement a = compare(*accel, tris, rays);
  EXPECT_EQ(a.foundMismatch, 0u);
  EXPECT_EQ(a.tieMismatch, 0u);
  EXPECT_EQ(a.anyFoundMismatch, 0u);
  EXPECT_GT(a.hits, 0u);
}

}  // namespace
}  // namespace passtrace
