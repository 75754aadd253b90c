// Every GPU structure against brute force on thousands of random rays over
// several meshes, and against the CPU running the kernel's own algorithm:
// the same hits and the same step counts, for every loop limit.

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "accel/stream_mirror_accelerators.h"
#include "accel/gpu_traversal.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

struct GpuCase {
  int accelerator;  // GPU column of thesis Table 4
  GridKernels gridKernels;
  std::string name;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
};

const std::vector<GpuCase>& gpuCases() {
  static const std::vector<GpuCase> cases = {{0, GridKernels::Merged, "kk_bvh"},
                                             {1, GridKernels::Merged, "gs_bvh"},
                                             {2, GridKernels::Merged, "kd_restart"},
                                             {3, GridKernels::Merged, "kd_backtrack"},
                                             {4, GridKernels::Merged, "grid"},
                                             {4, GridKernels::Split, "grid_split"},
                                             // --triangle-test watertight, in the kernels and on the CPU
                                             {0, GridKernels::Merged, "kk_bvh_watertight", TriangleTest::Watertight},
                                             {1, GridKernels::Merged, "gs_bvh_watertight", TriangleTest::Watertight},
                                             {2, GridKernels::Merged, "kd_restart_watertight", TriangleTest::Watertight},
                                             {3, GridKernels::Merged, "kd_backtrack_watertight", TriangleTest::Watertight},
                                             {4, GridKernels::Merged, "grid_watertight", TriangleTest::Watertight},
                                             {4, GridKernels::Split, "grid_split_watertight", TriangleTest::Watertight}};
  return cases;
}

// The CPU accelerator that runs the same algorithm over the same data.
std::unique_ptr<CpuAccelerator> cpuTwin(int gpuAccelerator, std::span<const Triangle> tris,
                                        const AccelBuildConfig& config) {
  switch (gpuAccelerator) {
    case 0: return makeCpuAccelerator(0, tris, config);
    case 1: return makeCpuAccelerator(1, tris, config);
    case 2: return makeStreamMirrorAccelerator(StreamMirror::KdRestart, tris, config);
    case 3: return makeStreamMirrorAccelerator(StreamMirror::KdBacktrack, tris, config);
    default: return makeStreamMirrorAccelerator(StreamMirror::Grid, tris, config);
  }
}

class GpuTraversalAgreement : public test::GlTest,
                              public ::testing::WithParamInterface<std::tuple<size_t, size_t>> {};

TEST_P(GpuTraversalAgreement, SameHitsAsBruteForceAndSameStepsAsTheCpu) {
  const GpuCase& c = gpuCases().at(std::get<0>(GetParam()));
  const testmesh::NamedMesh mesh = testmesh::standardMeshes().at(std::get<1>(GetParam()));
  Scene scene;
  scene.triangles = mesh.tris;
  scene.materialIds.assign(mesh.tris.size(), 0);
  scene.materials = {Material{}};
  AccelBuildConfig build;
  build.triangleTest = c.triangleTest;
  const auto cpu = cpuTwin(c.accelerator, scene.triangles, build);

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
    const auto traversal = makeGpuTraversal(c.accelerator, scene, GpuTraversalConfig{build, loopLimit, c.gridKernels});
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

INSTANTIATE_TEST_SUITE_P(
    AllStructures, GpuTraversalAgreement,
    ::testing::Combine(::testing::Range(size_t(0), gpuCases().size()),
                       ::testing::Range(size_t(0), testmesh::standardMeshes().size())),
    [](const auto& info) {
      return gpuCases().at(std::get<0>(info.param)).name + "_" +
             testmesh::standardMeshes().at(std::get<1>(info.param)).name;
    });

}  // namespace
}  // namespace passtrace
