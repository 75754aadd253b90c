// The stream path's cone queries (kernels_glsl/cone/kd_cone.frag and
// bvh_cone.frag) against the CPU's (KdConeTraversal, BvhConeTraversal): the same count, nearest id and t on every pixel
// and the same nodes and triangle references per cone, at loop limits 3 and
// 64 (the state resumes across passes), with and without --cone-max.
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "accel/cone/cone_tests.h"
#include "accel/cone/cone_traversal.h"
#include "render/gpu_cone_tracer.h"
#include "stream/inout_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"
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

// Every pixel: the same count, nearest id and t, nodes and triangle references.
void expectSameFrames(const ConeFrame& expected, const ConeFrame& actual) {
  ASSERT_EQ(actual.hits.size(), expected.hits.size());
  for (size_t i = 0; i < expected.hits.size(); ++i) {
    ASSERT_EQ(actual.hits[i].count, expected.hits[i].count) << "pixel " << i;
    EXPECT_EQ(actual.hits[i].id, expected.hits[i].id) << "pixel " << i;
    EXPECT_EQ(actual.hits[i].t, expected.hits[i].t) << "pixel " << i;
    EXPECT_EQ(actual.nodes[i], expected.nodes[i]) << "pixel " << i;
    EXPECT_EQ(actual.triangles[i], expected.triangles[i]) << "pixel " << i;
  }
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
  ASSERT_NO_FATAL_FAILURE(expectSameFrames(cpu, gpu));
  size_t met = 0, several = 0;
  for (size_t i = 0; i < cpu.hits.size(); ++i) {
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

struct ConeTriangleCase {
  Cone cone;
  Triangle tri;
};

struct ConeTriangleResult {
  bool met;
  float t;
};

// coneMeetsTriangle in GLSL (kernels_glsl/cone/cone_tests.glsl through
// test_functions.frag's TEST_CONE_TRIANGLE), one case per element.
std::vector<ConeTriangleResult> coneTriangleOnGpu(const std::vector<ConeTriangleCase>& cases) {
  const int width = int(std::min<size_t>(cases.size(), 1024)), height = int((cases.size() + width - 1) / width);
  std::vector<float> data(size_t(width) * height * 32, 0.0f);
  const auto pushDouble = [](float* out, double x) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    const uint32_t lo = uint32_t(b), hi = uint32_t(b >> 32);
    std::memcpy(out, &lo, 4);
    std::memcpy(out + 1, &hi, 4);
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    float* c = &data[32 * i];
    const Cone& cone = cases[i].cone;
    const Triangle& tri = cases[i].tri;
    for (int k = 0; k < 3; ++k) {
      c[k] = cone.apex[k];
      c[3 + k] = tri.v0[k];
      c[6 + k] = tri.v1[k];
      c[9 + k] = tri.v2[k];
    }
    // As render/gpu_cone_tracer.cpp hands them to the cone kernels.
    const glm::dvec3 v = glm::normalize(glm::dvec3(cone.axis));
    for (int k = 0; k < 3; ++k) pushDouble(c + 12 + 2 * k, v[k]);
    pushDouble(c + 18, std::cos(double(cone.halfAngle)));
    pushDouble(c + 20, std::sin(double(cone.halfAngle)));
  }
  StorageBuffer buffer("cone/triangle cases");
  buffer.upload(data);
  InOutStream out(width, height, 1);
  StreamKernel kernel("cone triangle", "test_functions.frag", StreamKernel::Depth::Test, {"TEST_CONE_TRIANGLE"});
  kernel.bindStorage(0, buffer);
  kernel.set("uWidth", width);
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  kernel.execute();
  out.disable();
  const std::vector<glm::vec4> texels = out.read(0);
  std::vector<ConeTriangleResult> results(cases.size());
  for (size_t i = 0; i < cases.size(); ++i) results[i] = {texels[i].x != 0.0f, texels[i].y};
  return results;
}

// Random cones and triangles, and cones whose surface passes through a
// vertex or touches an edge to within rounding: the exact test's borderline.
std::vector<ConeTriangleCase> coneTriangleCases() {
  std::mt19937 rng(2020);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), angle(0.0005f, 0.2f);
  std::vector<ConeTriangleCase> cases;
  for (int i = 0; i < 6000; ++i) {
    Cone cone;
    cone.apex = glm::vec3(u(rng), u(rng), u(rng) + 4.0f);
    const glm::vec3 target(0.6f * u(rng), 0.6f * u(rng), 0.0f);
    cone.axis = glm::normalize(target - cone.apex);
    const glm::vec3 centre(0.3f * u(rng), 0.3f * u(rng), 0.3f * u(rng));
    const float size = i % 3 == 0 ? 0.02f : 0.3f;
    Triangle tri{centre + size * glm::vec3(u(rng), u(rng), u(rng)), centre + size * glm::vec3(u(rng), u(rng), u(rng)),
                 centre + size * glm::vec3(u(rng), u(rng), u(rng))};
    cone.halfAngle = angle(rng);
    if (i % 2 == 1) {
      // Borderline: the least half-angle at which the C++ test meets the
      // triangle (bisected), nudged by up to two float ulps either way.
      float lo = 0.0f, hi = 1.2f, t;
      cone.halfAngle = hi;
      if (!coneMeetsTriangle(cone, tri, t)) continue;
      for (int k = 0; k < 40; ++k) {
        cone.halfAngle = 0.5f * (lo + hi);
        (coneMeetsTriangle(cone, tri, t) ? hi : lo) = cone.halfAngle;
      }
      float h = hi;
      for (int k = int(rng() % 5) - 2; k != 0; k += k > 0 ? -1 : 1) h = std::nextafter(h, k > 0 ? 2.0f : 0.0f);
      cone.halfAngle = h;
    }
    cases.push_back({cone, tri});
  }
  return cases;
}

// The GLSL exact test is the C++ one operation for operation (fp64 in the
// shader, no fused multiply-adds): the same verdict and the same t, bit for
// bit, borderline cases included.
TEST_F(GlTest, ConeTriangleTestMatchesCpp) {
  const std::vector<ConeTriangleCase> cases = coneTriangleCases();
  const std::vector<ConeTriangleResult> gpu = coneTriangleOnGpu(cases);
  size_t met = 0, mismatches = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    float t = 0.0f;
    const bool cpu = coneMeetsTriangle(cases[i].cone, cases[i].tri, t);
    met += cpu;
    if ((gpu[i].met != cpu || (cpu && gpu[i].t != t)) && mismatches++ < 10)
      ADD_FAILURE() << "case " << i << ": cpu " << cpu << " t " << t << ", gpu " << gpu[i].met << " t " << gpu[i].t;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(met, cases.size() / 5) << "the cases should meet and miss";
  EXPECT_LT(met, cases.size() * 4 / 5) << "the cases should meet and miss";
}

// Passes long enough to meet llvmpipe's loop cap (stream/shader_loop_budget.h):
// cones meeting hundreds of triangles each of a dense sphere, the whole
// traversal in one pass (-l 100000), with the --cone-max 0 set and a long
// sorted list. Without the kernels' work budget the cap cut leaves and list
// shifts short: wrong counts, without an error.
TEST_F(GlTest, GpuConesKeepEveryTriangleInLongPasses) {
  const std::vector<Triangle> tris = testmesh::uvSphere(90, 120, glm::vec3(0.0f), 0.8f);
  const CameraBasis camera = coneCamera(8);
  const float halfAngle = float(3.0 * std::numbers::pi / 180.0);
  const AccelBuildConfig build;
  for (const bool bvh : {false, true})
    for (const uint32_t maxHits : {0u, 1500u}) {
      SCOPED_TRACE(std::string(bvh ? "kk-bvh" : "kd-tree") + " --cone-max " + std::to_string(maxHits));
      const ConeQueryConfig config{maxHits};
      const ConeFrame cpu = traceCones(bvh ? *makeKkBvhCone(tris, build) : *makeKdTreeCone(tris, build), camera,
                                       halfAngle, config, 1);
      const ConeFrame gpu = traceConesGpu(bvh ? makeKkBvhStreamCone(tris, build) : makeKdTreeStreamCone(tris, build),
                                          camera, halfAngle, config, GpuConeConfig{100000, 8192});
      ASSERT_NO_FATAL_FAILURE(expectSameFrames(cpu, gpu));
      uint32_t most = 0;
      for (const ConeHitRecord& h : cpu.hits) most = std::max(most, h.count);
      EXPECT_GT(most, 500u) << "some cones should meet hundreds of triangles";
    }
}

// Cones traced in bands (records too large for one storage buffer): each
// band its own stream, a partial last row included, the same buffers.
TEST_F(GlTest, GpuConeBandsGiveTheSameBuffers) {
  const std::vector<Triangle> tris = coneMesh();
  const AccelBuildConfig build;
  const CameraBasis camera = coneCamera(20);
  const float halfAngle = float(2.5 * std::numbers::pi / 180.0);
  for (const bool bvh : {false, true}) {
    const ConeStreamTree tree = bvh ? makeKkBvhStreamCone(tris, build) : makeKdTreeStreamCone(tris, build);
    const ConeFrame whole = traceConesGpu(tree, camera, halfAngle, ConeQueryConfig{0}, GpuConeConfig{64, 64});
    // 64 set slots + header + stack: 37 cones' records per band, 11 bands.
    const uint64_t stride = 12 + 3 * tree.stackSize + 128;
    const ConeFrame bands =
        traceConesGpu(tree, camera, halfAngle, ConeQueryConfig{0}, GpuConeConfig{64, 64, 37 * stride * 4});
    ASSERT_NO_FATAL_FAILURE(expectSameFrames(whole, bands));
    size_t met = 0;
    for (const ConeHitRecord& h : whole.hits) met += h.count > 0;
    EXPECT_GT(met, whole.hits.size() / 4);
  }
}

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
