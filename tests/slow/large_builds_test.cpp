// Builds of bunny-sized and larger meshes (70k-100k triangles): the trees
// stay valid and their hits agree with brute force. Build times are the
// benchmark's to measure (scripts/bench.py), not these tests'.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/cpu_accelerator.h"
#include "accel/registry.h"
#include "tests/kd_checks.h"
#include "tests/registry_helpers.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::kd::compare;
using test::kd::expectAgreement;

TEST(KayKajiyaBvh, LargeSoupBuilds) {
  // Bunny-sized (the thesis's bunny has 69,451 triangles).
  const auto tris = testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.02f, 8);
  const Bvh bvh = buildKayKajiya(tris);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris);
  EXPECT_EQ(bvh.leafCount(), tris.size());
  EXPECT_EQ(seq.texels.size(), 2 * (tris.size() - 1) + 3 * tris.size());
  EXPECT_LT(bvh.depth(), 64u);
}

TEST(KdTree, LargeMeshesBuild) {
  struct Case {
    std::string name;
    std::vector<Triangle> tris;
  };
  std::vector<Case> cases;
  cases.push_back({"soup100k", testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.05f, 2005)});
  cases.push_back({"sphere70k (bunny-sized)", testmesh::uvSphere(190, 184)});
  cases.push_back({"soup70k (bunny-sized)", testmesh::triangleSoup(69451, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.06f, 6)});
  for (const Case& c : cases) {
    for (const int number : {2, 3}) {
      const auto accel = testing_registry::cpuStructure(number, c.tris);
      const AccelStats s = accel->stats();
      EXPECT_GT(s.nodes, 1000u);
      EXPECT_GE(s.buildMs, 0.0);
      // A few rays against brute force.
      const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(c.tris), 25, 3);
      expectAgreement(compare(*accel, c.tris, rays), c.name + " " + s.name);
    }
  }
}

// Every CPU structure of the registry on a 100k-triangle soup.
class CpuStructureLargeSoup : public ::testing::TestWithParam<std::string> {};

TEST_P(CpuStructureLargeSoup, BuildsAndHits) {
  const auto tris = testmesh::triangleSoup(100000, Aabb{glm::vec3(-1), glm::vec3(1)}, 0.03f, 99);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 500, 1);
  const auto accel = makeCpuStructure(*findStructure(GetParam()), tris);
  size_t hits = 0;
  for (const Ray& ray : rays) hits += accel->intersect(ray, false, nullptr).found();
  EXPECT_GT(hits, 0u);
}


// Every row with a CPU structure: the CPU renderer's and Embree's.
std::vector<std::string> cpuStructureNames() {
  std::vector<std::string> names;
  for (const Structure& s : structures())
    if (s.cpu) names.emplace_back(s.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllStructures, CpuStructureLargeSoup, ::testing::ValuesIn(cpuStructureNames()),
                         testing_registry::CaseNameOfRow());

}  // namespace
}  // namespace passtrace
