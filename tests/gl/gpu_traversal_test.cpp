// Every GPU structure against brute force on thousands of random rays over
// several meshes, and against the CPU running the kernel's own algorithm:
// the same hits and the same step counts, for every loop limit.

#include <gtest/gtest.h>

#include <algorithm>

#include "accel/brute_force.h"
#include "accel/registry.h"
#include "accel/gpu_traversal.h"
#include "scenes/scene.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

// Every stream structure of the registry, with each --grid-kernels variant
// it reads, under both triangle tests; and, under Moller-Trumbore only (the
// variants change the tree or the stack, not the triangle test), stack sizes
// 1 and 8 where it reads --stack-size and the binned kd build with thesis and
// papay termination where it reads --kd-builder, the sbvh and middle builds
// where it reads --bvh-builder.
struct GpuCase {
  const Structure* structure;
  GridKernels gridKernels;
  std::string name;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
  int stackSize = AccelBuildConfig{}.kdStackSize;
  KdBuilderKind kdBuilder = KdBuilderKind::Exact;
  KdTermination kdTermination = KdTermination::Thesis;
  BvhBuilderKind bvhBuilder = BvhBuilderKind::Sah;
};

const std::vector<GpuCase>& gpuCases() {
  static const std::vector<GpuCase> cases = [] {
    std::vector<GpuCase> cases;
    for (const TriangleTest test : {TriangleTest::MollerTrumbore, TriangleTest::Watertight})
      for (const Structure& s : structures()) {
        if (!s.runsOn(RendererId::Gpu)) continue;
        std::string name = testing_registry::caseName(s.name);
        const std::string suffix = test == TriangleTest::Watertight ? "_watertight" : "";
        cases.push_back({&s, GridKernels::Merged, name + suffix, test});
        const auto reads = s.readsOn(RendererId::Gpu);
        if (std::find(reads.begin(), reads.end(), BuildParam::GridKernels) != reads.end())
          cases.push_back({&s, GridKernels::Split, name + "_split" + suffix, test});
        if (test != TriangleTest::MollerTrumbore) continue;
        if (std::find(reads.begin(), reads.end(), BuildParam::KdStackSize) != reads.end())
          for (int k : {1, 8})
            cases.push_back({&s, GridKernels::Merged, name + "_stack" + std::to_string(k), test, k});
        if (std::find(reads.begin(), reads.end(), BuildParam::KdBuilder) != reads.end()) {
          const int k = AccelBuildConfig{}.kdStackSize;
          cases.push_back({&s, GridKernels::Merged, name + "_binned", test, k, KdBuilderKind::Binned});
          cases.push_back({&s, GridKernels::Merged, name + "_binned_papay", test, k, KdBuilderKind::Binned,
                           KdTermination::Papay});
        }
        if (std::find(reads.begin(), reads.end(), BuildParam::BvhBuilder) != reads.end()) {
          const int k = AccelBuildConfig{}.kdStackSize;
          for (const BvhBuilderKind b : {BvhBuilderKind::Sbvh, BvhBuilderKind::Middle})
            cases.push_back({&s, GridKernels::Merged, name + "_" + std::string(kBvhBuilderNames[int(b)]), test, k,
                             KdBuilderKind::Exact, KdTermination::Thesis, b});
        }
      }
    return cases;
  }();
  return cases;
}

// One case on one mesh: the GPU's hits and steps against brute force and the CPU mirror.
void expectGpuAgreement(const GpuCase& c, const testmesh::NamedMesh& mesh) {
  SCOPED_TRACE(mesh.name + " / " + c.name);
  Scene scene;
  scene.triangles = mesh.tris;
  scene.materialIds.assign(mesh.tris.size(), 0);
  scene.materials = {Material{}};
  AccelBuildConfig build;
  build.triangleTest = c.triangleTest;
  build.kdStackSize = c.stackSize;
  build.kdBuilder = c.kdBuilder;
  build.kdTermination = c.kdTermination;
  build.bvhBuilder = c.bvhBuilder;
  // The CPU running the same algorithm over the same data.
  const auto cpu = makeMirrorStructure(*c.structure, scene.triangles, build);

  std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(mesh.tris), 500, 42);
  std::vector<bool> shadow(rays.size(), false);
  const size_t n = rays.size();
  for (size_t i = 0; i < n; ++i) {  // a second copy as shadow rays with finite tMax
    Ray r = rays[i];
    r.tMax = 0.5f + float(i % 7);
    rays.push_back(r);
    shadow.push_back(true);
  }
  std::vector<test::TracedRays> gpu;
  for (int loopLimit : {3, 64}) {
    const auto traversal = makeStreamStructure(*c.structure, scene.triangles, GpuTraversalConfig{build, loopLimit, c.gridKernels});
    gpu.push_back(test::traceOnGpu(*traversal, rays, shadow));
  }
  size_t found = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool anyHit = shadow[i];
    const Hit brute = intersectBruteForce(mesh.tris, rays[i], anyHit, nullptr, c.triangleTest);
    RayStats stats;
    const Hit twin = cpu->intersect(rays[i], anyHit, &stats);
    const std::string what = "ray " + std::to_string(i) + (anyHit ? " (shadow)" : "");
    for (const test::TracedRays& g : gpu) {
      const Hit& h = g.hits[i];
      EXPECT_EQ(h.found(), brute.found()) << what;
      if (!anyHit && h.found() && brute.found() && h.id != brute.id) {
        EXPECT_NEAR(h.t, brute.t, 1e-5f * std::max(1.0f, brute.t)) << what << " (not a tie)";
      }
      if (h.id != twin.id) {  // only where triangles meet at the same t, one ulp apart on different hardware
        EXPECT_NEAR(h.t, twin.t, 1e-5f * std::max(1.0f, twin.t)) << what << " (not a tie)";
      }
      EXPECT_EQ(g.state[i].y, float(stats.steps)) << what;
      EXPECT_EQ(g.state[i].z, float(stats.triangleTests)) << what;
    }
    found += brute.found();
  }
  EXPECT_GT(found, rays.size() / 10);
  EXPECT_GE(gpu[0].passes, gpu[1].passes);
}

// One test per case, over every standard mesh: the meshes are small, and one
// process with one GL context per case costs a tenth of one per mesh.
class GpuTraversalAgreement : public test::GlTest, public ::testing::WithParamInterface<size_t> {};

TEST_P(GpuTraversalAgreement, SameHitsAsBruteForceAndSameStepsAsTheCpu) {
  for (const testmesh::NamedMesh& mesh : testmesh::standardMeshes()) expectGpuAgreement(gpuCases().at(GetParam()), mesh);
}

INSTANTIATE_TEST_SUITE_P(AllStructures, GpuTraversalAgreement, ::testing::Range(size_t(0), gpuCases().size()),
                         [](const auto& info) { return gpuCases().at(info.param).name; });

}  // namespace
}  // namespace passtrace
