// The escape-index BVH on the GPU, on the CPU (sequential and recursive) and
// brute force agree on thousands of random rays over several meshes.

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "accel/bvh_traversal.h"
#include "render/gpu_traversal.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

// Ids may differ only where two triangles are hit at the same t.
void expectSameHit(const Hit& actual, const Hit& expected, const std::string& what) {
  EXPECT_EQ(actual.found(), expected.found()) << what;
  if (actual.id != expected.id && actual.found() && expected.found()) {
    EXPECT_NEAR(actual.t, expected.t, 1e-5f * std::max(1.0f, std::abs(expected.t))) << what << " (a tie?)";
  }
}

class GpuBvhAgreement : public test::GlTest, public ::testing::WithParamInterface<int> {};

TEST_P(GpuBvhAgreement, GpuCpuAndBruteForceFindTheSameHits) {
  const testmesh::NamedMesh mesh = testmesh::standardMeshes().at(size_t(GetParam()));
  SCOPED_TRACE(mesh.name);
  Scene scene;
  scene.triangles = mesh.tris;
  scene.materialIds.assign(mesh.tris.size(), 0);
  scene.materials = {Material{}};
  const auto traversal = makeGpuTraversal(0, scene, GpuTraversalConfig{{}, 20});
  const auto sequential = makeCpuAccelerator(0, scene.triangles);
  const auto recursive = makeCpuAccelerator(5, scene.triangles);

  std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(mesh.tris), 800, 42);
  std::vector<bool> shadow(rays.size(), false);
  // A second copy as shadow rays with finite tMax: any hit before it counts.
  const size_t n = rays.size();
  for (size_t i = 0; i < n; ++i) {
    Ray r = rays[i];
    r.tMax = 0.5f + float(i % 7);
    rays.push_back(r);
    shadow.push_back(true);
  }
  const test::TracedRays gpu = test::traceOnGpu(*traversal, rays, shadow);
  size_t found = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool anyHit = shadow[i];
    const Hit brute = intersectBruteForce(mesh.tris, rays[i], anyHit);
    RayStats seqStats, recStats;
    const Hit seq = sequential->intersect(rays[i], anyHit, &seqStats);
    const Hit rec = recursive->intersect(rays[i], anyHit, &recStats);
    const std::string what = "ray " + std::to_string(i) + (anyHit ? " (shadow)" : "");
    if (anyHit) {
      EXPECT_EQ(gpu.hits[i].found(), brute.found()) << what;
      EXPECT_EQ(seq.found(), brute.found()) << what;
    } else {
      expectSameHit(gpu.hits[i], brute, "GPU " + what);
      expectSameHit(seq, brute, "CPU " + what);
      expectSameHit(rec, brute, "CPU recursive " + what);
    }
    // GPU and CPU run the same algorithm: the same steps and tests.
    EXPECT_EQ(gpu.state[i].y, float(seqStats.steps)) << what;
    EXPECT_EQ(gpu.state[i].z, float(seqStats.triangleTests)) << what;
    EXPECT_EQ(seqStats.steps, recStats.steps) << what;
    found += brute.found();
  }
  EXPECT_GT(found, rays.size() / 10) << "the rays should hit the mesh often";
}

INSTANTIATE_TEST_SUITE_P(Meshes, GpuBvhAgreement,
                         ::testing::Range(0, int(testmesh::standardMeshes().size())),
                         [](const auto& info) { return testmesh::standardMeshes().at(size_t(info.param)).name; });

}  // namespace
}  // namespace passtrace
