// --dynamic two-trees and merge on the GPU stream path
// (accel/kd/gpu_kd_dynamic.h): over two frames (the moving triangles in
// place, then moved partly out of the static bounds, the data replaced
// between them), nearest and shadow rays find what brute force finds, with
// the same step and triangle-test counts as the CPU running the kernels'
// algorithm over the same trees; and the stream's depth buffer survives a
// save and restore.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/kd/gpu_kd_dynamic.h"
#include "accel/kd/kd_dynamic.h"
#include "accel/ray_stream_layout.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::GlTest;

TEST_F(GlTest, SavedDepthIsRestored) {
  InOutStream stream(8, 4, 1);
  stream.enable();
  stream.clearDepth(0.0f);  // every element finished (the compute stage keeps only active or not)
  stream.saveDepth();
  stream.clearDepth(1.0f);
  stream.restoreDepth();
  for (float d : stream.readDepth()) ASSERT_EQ(d, 0.0f);
  stream.disable();
}

std::vector<Triangle> moved(std::vector<Triangle> tris, const std::vector<uint8_t>& moving, const glm::vec3& offset) {
  for (size_t i = 0; i < tris.size(); ++i)
    if (moving[i]) tris[i] = Triangle{tris[i].v0 + offset, tris[i].v1 + offset, tris[i].v2 + offset};
  return tris;
}

TEST_F(GlTest, DynamicStrategiesOnTheStreamPathAgreeWithBruteForceAndTheCpu) {
  for (const testmesh::NamedMesh& mesh : testmesh::standardMeshes()) {
    std::vector<uint8_t> moving(mesh.tris.size(), 0);
    for (size_t i = 0; i < moving.size(); i += 3) moving[i] = 1;
    const Aabb bounds = testmesh::boundsOf(mesh.tris);
    const std::vector<Triangle> second = moved(mesh.tris, moving, 0.3f * bounds.extent() + glm::vec3(0.05f));
    for (const DynamicStrategy strategy : {DynamicStrategy::TwoTrees, DynamicStrategy::Merge})
      for (const KdStreamVariant variant : {KdStreamVariant::Restart, KdStreamVariant::Backtrack})
        for (const int loopLimit : {3, 64}) {
          GpuTraversalConfig config;
          config.loopLimit = loopLimit;
          KdDynamicTrees trees(strategy, mesh.tris, moving, config.build);
          trees.update(mesh.tris);
          GpuKdDynamicTraversal gpu(trees, variant, mesh.tris, config);
          for (const std::vector<Triangle>* frame : {&mesh.tris, &second}) {
            if (frame == &second) {
              trees.update(*frame);
              gpu.update(*frame);
            }
            std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(*frame), 60, 9);
            std::vector<bool> shadow(rays.size(), false);
            const size_t n = rays.size();
            for (size_t i = 0; i < n; ++i) {  // again as shadow rays with finite tMax
              Ray r = rays[i];
              r.tMax = 0.5f + float(i % 7);
              rays.push_back(r);
              shadow.push_back(true);
            }
            const test::TracedRays traced = test::traceOnGpu(gpu, rays, shadow);
            const auto cpu = makeKdDynamicCpu(trees, variant, *frame, TriangleTest::MollerTrumbore, "kd", 0.0);
            for (size_t i = 0; i < rays.size(); ++i) {
              const std::string what = mesh.name + " " + std::string(dynamicStrategyName(strategy)) +
                                       (variant == KdStreamVariant::Restart ? " restart" : " backtrack") + " -l " +
                                       std::to_string(loopLimit) + (frame == &second ? " moved" : " in place") +
                                       " ray " + std::to_string(i) + (shadow[i] ? " (shadow)" : "");
              const Hit brute = intersectBruteForce(*frame, rays[i], shadow[i]);
              RayStats stats;
              const Hit twin = cpu->intersect(rays[i], shadow[i], &stats);
              const Hit& h = traced.hits[i];
              ASSERT_EQ(h.found(), brute.found()) << what;
              if (!shadow[i] && h.found() && h.id != brute.id) {
                ASSERT_NEAR(h.t, brute.t, 1e-5f * std::max(1.0f, brute.t)) << what << " (not a tie)";
              }
              ASSERT_EQ(h.id, twin.id) << what;
              ASSERT_EQ(traced.state[i].y, float(stats.steps)) << what;
              ASSERT_EQ(traced.state[i].z, float(stats.triangleTests)) << what;
            }
          }
        }
  }
}

}  // namespace
}  // namespace passtrace
