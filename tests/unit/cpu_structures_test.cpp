// Every CPU structure of the registry (accel/registry.h, each row with a CPU
// factory, Embree's included) against brute force, on the standard meshes and
// one built on a uniform grid's cell boundaries, with random rays and rays
// starting on cell boundary planes. Closest hits may differ only in which of
// several triangles hit at the same t wins; any-hit queries must hit exactly
// when brute force does. A new registry row is tested here as it is.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/grid/uniform_grid.h"
#include "accel/grid/uniform_grid_builder.h"
#include "accel/registry.h"
#include "tests/hit_checks.h"
#include "tests/test_meshes.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

using test::sameHit;
using test::tiedT;

// The registry's rows that build on the CPU.
std::vector<const Structure*> cpuStructures() {
  std::vector<const Structure*> rows;
  for (const Structure& s : structures())
    if (s.cpu) rows.push_back(&s);
  return rows;
}

// Rays whose origins lie exactly on cell boundary planes (computed as the
// grid computes them), in random, axis-aligned and plane-parallel
// directions, some lying in the plane they start on, some aimed inside.
std::vector<Ray> boundaryRays(const UniformGrid& grid, size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Ray> rays;
  const glm::vec3 lo = grid.bounds.min, ext = grid.bounds.extent();
  for (size_t i = 0; i < count; ++i) {
    Ray ray;
    for (int k = 0; k < 3; ++k) ray.origin[k] = lo[k] + unit(rng) * ext[k];
    // One to three coordinates on a boundary (grid corners included).
    const int onPlanes = 1 + int(rng() % 3);
    for (int j = 0; j < onPlanes; ++j) {
      const int k = int(rng() % 3);
      const int boundary = int(rng() % uint64_t(grid.resolution[k] + 1));
      ray.origin[k] = boundary == grid.resolution[k] ? grid.bounds.max[k] : lo[k] + float(boundary) * grid.cellSize[k];
    }
    const int kind = int(rng() % 4);
    glm::vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
    if (glm::dot(d, d) < 1e-6f) d = glm::vec3(1, 0, 0);
    d = glm::normalize(d);
    if (kind == 1) {  // axis aligned
      const int k = int(rng() % 3);
      d = glm::vec3(0.0f);
      d[k] = rng() % 2 ? 1.0f : -1.0f;
    } else if (kind == 2) {  // parallel to one family of cell planes
      const int k = int(rng() % 3);
      d[k] = 0.0f;
      if (glm::dot(d, d) < 1e-6f) d[(k + 1) % 3] = 1.0f;
      d = glm::normalize(d);
      d[k] = 0.0f;
    } else if (kind == 3) {  // at a random point inside the bounds
      glm::vec3 target;
      for (int k = 0; k < 3; ++k) target[k] = lo[k] + unit(rng) * ext[k];
      if (target != ray.origin) d = glm::normalize(target - ray.origin);
    }
    ray.direction = d;
    if (rng() % 3 == 0) ray.tMax = unit(rng) * glm::length(ext);
    rays.push_back(ray);
  }
  return rays;
}

struct Agreement {
  size_t rays = 0, hits = 0, foundMismatch = 0, tieMismatch = 0, bogusAnyHit = 0;
};

// Embree is the baseline, not a structure of ours: its any-hit query reports
// occlusion only, not the hit (embree_accelerator.h), so its any hits are
// checked for presence alone, and it computes t by its own formula, so ties
// are judged at 1e-4 relative instead of 1e-6.
Agreement compareWithBruteForce(const Structure& s, const CpuAccelerator& accel, std::span<const Triangle> tris,
                                std::span<const Ray> rays, std::span<const Hit> closest) {
  const bool embree = s.runsOn(RendererId::Embree);
  const float tieTolerance = embree ? 1e-4f : 1e-6f;
  Agreement a;
  for (size_t i = 0; i < rays.size(); ++i)
    for (const bool anyHit : {false, true}) {
      const Ray& ray = rays[i];
      ++a.rays;
      const Hit h = accel.intersect(ray, anyHit, nullptr);
      const Hit& b = closest[i];  // an any hit exists exactly where a closest one does
      if (h.found() != b.found()) {
        ++a.foundMismatch;
        continue;
      }
      if (!h.found()) continue;
      ++a.hits;
      if (anyHit) {
        if (embree) continue;
        Hit check{ray.tMax};
        if (!intersectTriangle(ray.origin, ray.direction, tris[h.id], h.id, check) || !sameHit(check, h))
          ++a.bogusAnyHit;
      } else if (h.id != b.id && !tiedT(h.t, b.t, tieTolerance)) {
        ++a.tieMismatch;
      }
    }
  return a;
}

// Every CPU row with its default build, plus stack sizes 1 and 8 of the rows
// that read --stack-size and the binned SAH build (with the thesis's and the
// seed's termination) of the rows that read --kd-builder, and the SBVH build
// (suffix _sbvh) of the rows that read --bvh8-builder.
struct CpuCase {
  const Structure* structure;
  AccelBuildConfig config;
  std::string name;
};

const std::vector<CpuCase>& cpuCases() {
  static const std::vector<CpuCase> cases = [] {
    std::vector<CpuCase> cases;
    for (const Structure* s : cpuStructures()) {
      std::string name = testing_registry::caseName(s->name);
      cases.push_back({s, AccelBuildConfig{}, name});
      const auto reads = s->readsOn(RendererId::Cpu);
      if (std::find(reads.begin(), reads.end(), BuildParam::KdStackSize) != reads.end())
        for (int k : {1, 8}) {
          AccelBuildConfig config;
          config.kdStackSize = k;
          cases.push_back({s, config, name + "_stack" + std::to_string(k)});
        }
      if (std::find(reads.begin(), reads.end(), BuildParam::Bvh8Builder) != reads.end()) {
        AccelBuildConfig config;
        config.bvh8Builder = Bvh8BuilderKind::Sbvh;
        cases.push_back({s, config, name + "_sbvh"});
      }
      if (std::find(reads.begin(), reads.end(), BuildParam::KdBuilder) == reads.end()) continue;
      for (const KdTermination rule : {KdTermination::Thesis, KdTermination::Papay}) {
        AccelBuildConfig config;
        config.kdBuilder = KdBuilderKind::Binned;
        config.kdTermination = rule;
        cases.push_back({s, config, name + (rule == KdTermination::Papay ? "_binned_papay" : "_binned")});
      }
    }
    return cases;
  }();
  return cases;
}

// One case on one mesh: every ray's hit against brute force.
// A mesh's rays and brute force's closest hits on them, made once per process
// (keyed by the mesh and whether the cell-boundary rays are in): every case
// traces the same ones, and brute force per case was most of the sanitized
// run's unit time (which runs each shard's tests in one process).
struct ReferenceRays {
  std::vector<Ray> rays;
  std::vector<Hit> closest;
};
const ReferenceRays& referenceRays(const testmesh::NamedMesh& mesh, bool withBoundaryRays) {
  static std::map<std::pair<std::string, bool>, ReferenceRays> cache;
  auto [at, added] = cache.try_emplace({mesh.name, withBoundaryRays});
  if (added) {
    ReferenceRays& r = at->second;
    r.rays = testmesh::rayMix(testmesh::boundsOf(mesh.tris), 1000, 42);
    if (withBoundaryRays) {
      const std::vector<Ray> edge = boundaryRays(buildUniformGrid(mesh.tris), 2000, 9);
      r.rays.insert(r.rays.end(), edge.begin(), edge.end());
    }
    for (const Ray& ray : r.rays) r.closest.push_back(intersectBruteForce(mesh.tris, ray, false));
  }
  return at->second;
}

void expectCpuAgreement(const CpuCase& c, const testmesh::NamedMesh& mesh) {
  const Structure& s = *c.structure;
  // Rays starting on cell planes, many lying in a triangle's plane, test our
  // structures' watertight rules; Embree's triangle test is not watertight
  // (tests/gl/watertight_test.cpp bounds its leaks), so it meets random rays only.
  const ReferenceRays& reference = referenceRays(mesh, !s.runsOn(RendererId::Embree));
  const auto accel = makeCpuStructure(s, mesh.tris, c.config);
  const Agreement a = compareWithBruteForce(s, *accel, mesh.tris, reference.rays, reference.closest);
  const std::string what = mesh.name + " / " + c.name;
  EXPECT_EQ(a.foundMismatch, 0u) << what;
  EXPECT_EQ(a.tieMismatch, 0u) << what;
  EXPECT_EQ(a.bogusAnyHit, 0u) << what;
  EXPECT_GT(a.hits, 0u) << what;
}

// One test per case, over every mesh: the meshes are small, and a process per
// case costs a ninth of one per mesh.
class CpuStructureAgreement : public ::testing::TestWithParam<size_t> {};

TEST_P(CpuStructureAgreement, SameHitsAsBruteForce) {
  for (const testmesh::NamedMesh& mesh : testmesh::standardMeshesAndCellBoundaries())
    expectCpuAgreement(cpuCases().at(GetParam()), mesh);
}

INSTANTIATE_TEST_SUITE_P(AllStructures, CpuStructureAgreement, ::testing::Range(size_t(0), cpuCases().size()),
                         [](const auto& info) { return cpuCases().at(info.param).name; });

// Built without triangles nothing is hit and no step is taken; one triangle
// is hit; the structure carries its row's name.
TEST(CpuStructures, FactoryAndEmptyScenes) {
  const std::vector<Triangle> none;
  const std::vector<Triangle> single = testmesh::singleTriangle();
  for (const Structure* s : cpuStructures()) {
    const auto accel = makeCpuStructure(*s, none);
    RayStats stats;
    EXPECT_FALSE(accel->intersect(Ray{}, false, &stats).found());
    EXPECT_EQ(stats.steps, 0u);
    EXPECT_EQ(accel->name(), s->name);
    const auto viaMain = makeCpuStructure(*s, single);
    EXPECT_EQ(viaMain->name(), s->name);
    EXPECT_TRUE(viaMain->intersect(Ray{glm::vec3(-0.5f, -0.5f, 2.0f), glm::vec3(0, 0, -1)}, false, nullptr).found());
  }
}

}  // namespace
}  // namespace passtrace
