// DACRT (accel/dacrt/) against brute force: whole batches as the CPU renderer
// hands them over (primary rays from one eye, shadow rays to a light with
// finite tMax, incoherent rays), with and without conic packets, at the
// seed's limits and at rLimit = pLimit = 1; and its two filters, the
// triangle/cell and cone/cell tests, against brute-force sampling.

#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "accel/dacrt/cell_tests.h"
#include "accel/dacrt/dacrt_tracer.h"
#include "tests/hit_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::tiedT;

// A batch of rays laid out as a side x side image.
struct Batch {
  std::vector<Ray> rays;
  std::vector<uint8_t> active, anyHit;
  int side = 0;
  bool primary = false;
  std::optional<glm::vec3> light;

  RayBatch view(unsigned threads) const {
    return RayBatch{rays, active, anyHit, side, side, primary, light, threads};
  }
};

// An eye outside the bounds looking at their centre through side x side
// pixels that cover the bounds and a margin around them.
Batch primaryBatch(const Aabb& bounds, int side) {
  Batch b;
  b.side = side, b.primary = true;
  const glm::vec3 c = bounds.center();
  const float r = 0.5f * glm::length(bounds.extent()) + 1e-3f;
  const glm::vec3 eye = c + glm::vec3(0.37f, 0.52f, 1.0f) * (2.5f * r);
  const glm::vec3 forward = glm::normalize(c - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const float sx = (2.0f * (float(x) + 0.5f) / float(side) - 1.0f) * 0.5f;
      const float sy = (1.0f - 2.0f * (float(y) + 0.5f) / float(side)) * 0.5f;
      b.rays.push_back(Ray{eye, glm::normalize(forward + sx * right + sy * up), kInfinity});
      b.active.push_back(uint8_t((x * 7 + y * 3) % 11 != 0));  // some pixels have no ray
      b.anyHit.push_back(0);
    }
  return b;
}

// Shadow rays from the primary hits (or points inside the bounds for the
// misses) to a light, tMax the distance to it, plus every fifth a mirror ray
// (nearest hit, no common origin), as the renderer's second generation.
Batch shadowBatch(std::span<const Triangle> tris, const Aabb& bounds, int side) {
  const Batch primary = primaryBatch(bounds, side);
  Batch b;
  b.side = side;
  const glm::vec3 light = bounds.max + 0.3f * bounds.extent() + glm::vec3(1e-3f);
  b.light = light;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (size_t i = 0; i < primary.rays.size(); ++i) {
    const Ray& p = primary.rays[i];
    const Hit h = intersectBruteForce(tris, p, false);
    glm::vec3 origin;
    if (h.found()) origin = p.origin + h.t * p.direction - 1e-4f * p.direction;
    else
      for (int k = 0; k < 3; ++k) origin[k] = bounds.min[k] + unit(rng) * bounds.extent()[k];
    const bool mirror = i % 5 == 0;
    if (mirror) {
      glm::vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
      b.rays.push_back(Ray{origin, glm::normalize(d + glm::vec3(1e-3f)), kInfinity});
    } else {
      const float distance = glm::length(light - origin);
      b.rays.push_back(Ray{origin, (light - origin) / distance, distance});
    }
    b.active.push_back(primary.active[i]);
    b.anyHit.push_back(uint8_t(!mirror));
  }
  return b;
}

// Incoherent rays of every kind (half with finite tMax), half of them shadow queries.
Batch mixedBatch(const Aabb& bounds) {
  Batch b;
  b.rays = testmesh::rayMix(bounds, 600, 42);
  for (size_t i = 0; i < b.rays.size(); ++i) {
    b.active.push_back(1);
    b.anyHit.push_back(uint8_t(i % 2));
  }
  return b;
}

struct Mismatches {
  size_t found = 0, nearest = 0, bogusAnyHit = 0, hits = 0;
};

// Brute force on each active ray of b (any hit for its shadow queries).
std::vector<Hit> bruteForceHits(std::span<const Triangle> tris, const Batch& b) {
  std::vector<Hit> hits(b.rays.size());
  for (size_t i = 0; i < b.rays.size(); ++i)
    if (b.active[i]) hits[i] = intersectBruteForce(tris, b.rays[i], b.anyHit[i] != 0);
  return hits;
}

Mismatches compare(std::span<const Triangle> tris, const Batch& b, std::span<const Hit> reference,
                   const dacrt::Settings& settings) {
  std::vector<Hit> hits(b.rays.size());
  std::vector<RayStats> stats(b.rays.size());
  const FilterStats counters = dacrt::trace(tris, settings, b.view(2), hits, stats);
  Mismatches m;
  for (size_t i = 0; i < b.rays.size(); ++i) {
    if (!b.active[i]) continue;
    const Ray& ray = b.rays[i];
    const Hit& ref = reference[i];
    const Hit& h = hits[i];
    if (h.found() != ref.found()) {
      ++m.found;
      continue;
    }
    if (!h.found()) {
      if (h.t != ray.tMax) ++m.found;  // a miss reports tMax, as brute force
      continue;
    }
    ++m.hits;
    if (b.anyHit[i]) {
      Hit check{ray.tMax};
      if (!intersectTriangle(ray.origin, ray.direction, tris[h.id], h.id, check) || check.t != h.t) ++m.bogusAnyHit;
    } else if (h.id != ref.id && !tiedT(h.t, ref.t)) {
      ++m.nearest;
    } else if (h.id == ref.id && (h.t != ref.t || h.u != ref.u || h.v != ref.v)) {
      ++m.nearest;
    }
  }
  EXPECT_GT(counters.nodes, 0u);
  return m;
}

struct Variant {
  const char* name;
  int rLimit, pLimit;
  bool cones;
  bool median;
};
constexpr Variant kVariants[] = {
    {"defaults", 20, 16, false, false}, {"cones", 20, 16, true, false}, {"limits_1_1", 1, 1, false, false},
    {"cones_1_1", 1, 1, true, false},   {"median", 20, 16, false, true}, {"big_limits", 200, 100, true, false}};

std::vector<testmesh::NamedMesh> meshes() {
  std::vector<testmesh::NamedMesh> all = testmesh::standardMeshes();
  // Above 10,000 triangles: the sampled-mean split.
  all.push_back({"dense_sphere", testmesh::uvSphere(80, 80)});
  return all;
}

class DacrtAgreement : public ::testing::TestWithParam<std::tuple<size_t, size_t>> {};

// A mesh's three batches and brute force's hits on them, made once per
// process: every variant traces the same ones, and recomputing brute force
// over the dense sphere per variant was a minute of the sanitized run (which
// runs each shard's tests in one process).
struct ReferenceBatch {
  std::string what;
  Batch batch;
  std::vector<Hit> hits;
};
const std::vector<ReferenceBatch>& referenceBatches(size_t meshIndex) {
  static std::map<size_t, std::vector<ReferenceBatch>> cache;
  auto [at, added] = cache.try_emplace(meshIndex);
  if (added) {
    const std::vector<Triangle> tris = meshes().at(meshIndex).tris;
    const Aabb bounds = testmesh::boundsOf(tris);
    const int side = 48;  // 6 x 6 packets
    for (auto& [what, batch] : {std::pair{"primary", primaryBatch(bounds, side)},
                                std::pair{"shadow", shadowBatch(tris, bounds, side)},
                                std::pair{"mixed", mixedBatch(bounds)}})
      at->second.push_back({what, batch, bruteForceHits(tris, batch)});
  }
  return at->second;
}

TEST_P(DacrtAgreement, BatchesEqualBruteForce) {
  const testmesh::NamedMesh mesh = meshes().at(std::get<0>(GetParam()));
  const Variant& v = kVariants[std::get<1>(GetParam())];
  dacrt::Settings settings;
  settings.rLimit = v.rLimit, settings.pLimit = v.pLimit, settings.cones = v.cones, settings.medianSplit = v.median;
  for (const ReferenceBatch& r : referenceBatches(std::get<0>(GetParam()))) {
    const Mismatches m = compare(mesh.tris, r.batch, r.hits, settings);
    SCOPED_TRACE(mesh.name + " / " + v.name + " / " + r.what);
    EXPECT_EQ(m.found, 0u);
    EXPECT_EQ(m.nearest, 0u);
    EXPECT_EQ(m.bogusAnyHit, 0u);
    EXPECT_GT(m.hits, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(MeshesAndLimits, DacrtAgreement,
                         ::testing::Combine(::testing::Range(size_t(0), meshes().size()),
                                            ::testing::Range(size_t(0), std::size(kVariants))),
                         [](const auto& info) {
                           return meshes().at(std::get<0>(info.param)).name + "_" +
                                  kVariants[std::get<1>(info.param)].name;
                         });

// Conic packets exist to cut the ray/box tests (the seed's Fig. 8).
TEST(Dacrt, ConesReplaceRayBoxTests) {
  const std::vector<Triangle> tris = testmesh::uvSphere(80, 80);
  const Batch b = primaryBatch(testmesh::boundsOf(tris), 128);
  std::vector<Hit> hits(b.rays.size());
  std::vector<RayStats> stats(b.rays.size());
  dacrt::Settings plain, cones;
  cones.cones = true;
  const FilterStats a = dacrt::trace(tris, plain, b.view(1), hits, stats);
  const FilterStats c = dacrt::trace(tris, cones, b.view(1), hits, stats);
  EXPECT_EQ(a.coneBox, 0u);
  EXPECT_GT(c.coneBox, 0u);
  EXPECT_LT(c.rayBox, a.rayBox / 2);
}

Aabb randomBox(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), size(0.05f, 1.0f);
  Aabb box;
  const glm::vec3 c(u(rng), u(rng), u(rng));
  const glm::vec3 h(size(rng), size(rng), size(rng));
  box.extend(c - h);
  box.extend(c + h);
  return box;
}

bool contains(const Aabb& box, const glm::vec3& p) {
  return p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y && p.z >= box.min.z &&
         p.z <= box.max.z;
}

// No triangle with a point in the cell is dropped; and the test does reject
// triangles (those it must: their bounds miss the cell).
TEST(DacrtCellTests, TriangleFilterIsConservative) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  size_t touching = 0, rejected = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Aabb box = randomBox(rng);
    Triangle t{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    if (trial % 7 == 0) t.v2 = t.v1;  // degenerate: a segment
    bool sampledInside = false;
    constexpr int kSteps = 24;
    for (int i = 0; i <= kSteps && !sampledInside; ++i)
      for (int j = 0; i + j <= kSteps && !sampledInside; ++j) {
        const float a = float(i) / kSteps, b = float(j) / kSteps;
        sampledInside = contains(box, t.v0 + a * (t.v1 - t.v0) + b * (t.v2 - t.v0));
      }
    const bool kept = dacrt::triangleTouchesCell(t, box);
    if (sampledInside) {
      ++touching;
      EXPECT_TRUE(kept) << "trial " << trial;
    }
    const Aabb tb = t.bounds();
    const bool boundsMiss = tb.max.x < box.min.x - 0.01f || tb.min.x > box.max.x + 0.01f ||
                            tb.max.y < box.min.y - 0.01f || tb.min.y > box.max.y + 0.01f ||
                            tb.max.z < box.min.z - 0.01f || tb.min.z > box.max.z + 0.01f;
    if (boundsMiss) {
      EXPECT_FALSE(kept) << "trial " << trial;
    }
    rejected += !kept;
  }
  EXPECT_GT(touching, 1000u);
  EXPECT_GT(rejected, 1000u);
}

// A triangle lying exactly in a cell face, or touching it at a vertex, touches it.
TEST(DacrtCellTests, TriangleOnTheCellBoundaryIsKept) {
  const Aabb box{glm::vec3(0.0f), glm::vec3(1.0f)};
  EXPECT_TRUE(dacrt::triangleTouchesCell(Triangle{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, box));
  EXPECT_TRUE(dacrt::triangleTouchesCell(Triangle{{1, 1, 1}, {2, 1, 1}, {1, 2, 3}}, box));
  EXPECT_TRUE(dacrt::triangleTouchesCell(Triangle{{-1, 0.5f, 0.5f}, {2, 0.5f, 0.5f}, {0.5f, 3, 0.5f}}, box));
  EXPECT_FALSE(dacrt::triangleTouchesCell(Triangle{{1.5f, 0, 0}, {3, 0, 0}, {1.5f, 3, 0}}, box));
  // Its bounds overlap the cell, but the triangle passes by a corner.
  EXPECT_FALSE(dacrt::triangleTouchesCell(Triangle{{0.9f, 3, 0.5f}, {3, 0.9f, 0.5f}, {3, 3, 0.5f}}, box));
}

// Points of the box inside the cone, and rays of the cone that enter the
// box, are never missed; cones that clearly pass the box are rejected.
TEST(DacrtCellTests, ConeTestAgreesWithSampling) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), angle(0.01f, 0.9f);
  size_t touching = 0, rejected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Aabb box = randomBox(rng);
    dacrt::Cone cone;
    cone.apex = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f;
    glm::vec3 axis(u(rng), u(rng), u(rng));
    if (trial % 2 == 0) axis = box.center() + 0.8f * glm::vec3(u(rng), u(rng), u(rng)) - cone.apex;  // near misses
    cone.axis = glm::normalize(axis + glm::vec3(1e-4f));
    const float alpha = angle(rng) * (trial % 3 == 0 ? 0.1f : 1.0f);
    cone.cosAngle = std::cos(alpha);
    // Brute force: the box's points (a 12^3 lattice, faces included).
    bool inside = contains(box, cone.apex);
    constexpr int kN = 12;
    for (int i = 0; i <= kN && !inside; ++i)
      for (int j = 0; j <= kN && !inside; ++j)
        for (int k = 0; k <= kN && !inside; ++k) {
          const glm::vec3 p = box.min + box.extent() * glm::vec3(i, j, k) / float(kN);
          const glm::vec3 w = p - cone.apex;
          inside = glm::dot(w, cone.axis) >= cone.cosAngle * glm::length(w);
        }
    const bool said = dacrt::coneTouchesCell(cone, box);
    if (inside) {
      ++touching;
      EXPECT_TRUE(said) << "trial " << trial;
    }
    // And the cone's own rays: any that enters the box must be kept.
    if (!said) {
      ++rejected;
      const glm::vec3 side = glm::normalize(glm::cross(cone.axis, glm::vec3(0.3f, 0.5f, 0.7f)));
      const glm::vec3 other = glm::cross(cone.axis, side);
      for (int r = 0; r < 64; ++r) {
        const float phi = 6.2831853f * float(r) / 64.0f, a = alpha * float(r % 8) / 7.0f;
        const glm::vec3 d = std::cos(a) * cone.axis + std::sin(a) * (std::cos(phi) * side + std::sin(phi) * other);
        EXPECT_FALSE(intersectsBox(cone.apex, safeInverse(d), box, kInfinity)) << "trial " << trial << " ray " << r;
      }
    }
  }
  EXPECT_GT(touching, 500u);
  EXPECT_GT(rejected, 500u);
}

}  // namespace
}  // namespace passtrace
