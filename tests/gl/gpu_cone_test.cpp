// The stream path's cone queries (kernels_glsl/cone/kd_cone.frag and
// bvh_cone.frag) against the CPU's (KdConeTraversal, BvhConeTraversal): the same count, nearest id and t on every pixel
// and the same nodes and triangle references per cone, at loop limits 3 and
// 64 (the state resumes across passes), with and without --cone-max.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "accel/cone/cone_traversal.h"
#include "render/gpu_cone_tracer.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace::test {
namespace {

std::vector<Triangle> coneMesh() {
  // A sphere (neighbouring triangles, shared edges) inside a soup whose
  // triangles straddle kd splits (repeated in several leaves).
  std::vector<Triangle> tris = testmesh::uvSphere(10, 14, glm::vec3(0.0f), 0.8f);
  const std::vector<Triangle> soup = testmesh::triangleSoup(150, Aabb{glm::vec3(-1.2f), glm::vec3(1.2f)}, 0.6f, 7);
  tris.insert(tris.end(), soup.begin(), soup.end());
  return tris;
}

CameraBasis coneCamera(int size) {
  CameraSpec spec;
  spec.eye = glm::vec3(0.3f, 0.4f, 3.0f);
  return makeCameraBasis(spec, size, size);
}

struct GpuConeCase {
  bool bvh;  // kk-bvh's tree (bvh_cone.frag), else the kd-tree's (kd_cone.frag)
  float degrees;
  uint32_t maxHits;
  int loopLimit;
};

class GpuCone : public GlTest, public ::testing::WithParamInterface<GpuConeCase> {};

TEST_P(GpuCone, SameBuffersAsCpu) {
  const GpuConeCase c = GetParam();
  const std::vector<Triangle> tris = coneMesh();
  const AccelBuildConfig build;
  const CameraBasis camera = coneCamera(20);
  const float halfAngle = float(double(c.degrees) * std::numbers::pi / 180.0);
  ConeQueryConfig config{c.maxHits};
  const ConeFrame cpu = traceCones(c.bvh ? *makeKkBvhCone(tris, build) : *makeKdTreeCone(tris, build), camera,
                                   halfAngle, config, 1);
  const ConeFrame gpu = traceConesGpu(c.bvh ? makeKkBvhStreamCone(tris, build) : makeKdTreeStreamCone(tris, build),
                                      camera, halfAngle, config, GpuConeConfig{c.loopLimit});
  ASSERT_EQ(gpu.hits.size(), cpu.hits.size());
  size_t met = 0, several = 0;
  for (size_t i = 0; i < cpu.hits.size(); ++i) {
    ASSERT_EQ(gpu.hits[i].count, cpu.hits[i].count) << "pixel " << i;
    EXPECT_EQ(gpu.hits[i].id, cpu.hits[i].id) << "pixel " << i;
    EXPECT_EQ(gpu.hits[i].t, cpu.hits[i].t) << "pixel " << i;
    EXPECT_EQ(gpu.nodes[i], cpu.nodes[i]) << "pixel " << i;
    EXPECT_EQ(gpu.triangles[i], cpu.triangles[i]) << "pixel " << i;
    met += cpu.hits[i].count > 0;
    several += cpu.hits[i].count > 1;
  }
  EXPECT_GT(met, cpu.hits.size() / 4) << "the mesh should fill part of the image";
  EXPECT_GT(several, 0u) << "some cones should meet several triangles";
}

INSTANTIATE_TEST_SUITE_P(Cones, GpuCone,
                         ::testing::Values(GpuConeCase{false, 0.5f, 0, 3}, GpuConeCase{false, 0.5f, 0, 64},
                                           GpuConeCase{false, 2.5f, 0, 3}, GpuConeCase{false, 2.5f, 0, 64},
                                           GpuConeCase{false, 2.5f, 3, 3}, GpuConeCase{false, 5.0f, 2, 64},
                                           GpuConeCase{true, 0.5f, 0, 3}, GpuConeCase{true, 2.5f, 0, 64},
                                           GpuConeCase{true, 2.5f, 3, 3}, GpuConeCase{true, 5.0f, 2, 64}),
                         [](const auto& info) {
                           return std::string(info.param.bvh ? "kkbvh" : "kd") + "_deg" + std::to_string(int(info.param.degrees * 10)) + "_max" +
                                  std::to_string(info.param.maxHits) + "_l" + std::to_string(info.param.loopLimit);
                         });

TEST_F(GlTest, GpuConeListOverflowIsAnError) {
  const std::vector<Triangle> tris = coneMesh();
  const float halfAngle = float(10.0 * std::numbers::pi / 180.0);
  const ConeStreamTree tree = makeKdTreeStreamCone(tris, AccelBuildConfig{});
  EXPECT_THROW(traceConesGpu(tree, coneCamera(4), halfAngle, ConeQueryConfig{0}, GpuConeConfig{64, 4}),
               std::runtime_error);
  EXPECT_THROW(traceConesGpu(tree, coneCamera(4), halfAngle, ConeQueryConfig{5}, GpuConeConfig{64, 4}),
               std::runtime_error);
}

}  // namespace
}  // namespace passtrace::test
