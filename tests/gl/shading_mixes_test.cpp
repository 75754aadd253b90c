// --shading whitted and ao: the AO hash and directions in GLSL against the
// C++, and the CPU and stream renderers' images of the same settings.

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "render/ao_sampling.h"
#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"
#include "scenes/scene_registry.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::GlTest;

std::vector<glm::vec4> runKernel(const char* define, const std::vector<std::vector<glm::vec4>>& inputs, int width) {
  const int n = int(inputs[0].size());
  InOutStream in(width, n / width, 2), out(width, n / width, 1);
  StreamKernel kernel("test", "test_functions.frag", StreamKernel::Depth::Test, {define});
  const char* names[] = {"uIn0", "uIn1"};
  for (size_t s = 0; s < inputs.size(); ++s) {
    in.upload(int(s), inputs[s]);
    kernel.bindInput(names[s], in, int(s));
  }
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  kernel.execute();
  out.disable();
  return out.read(0);
}

TEST_F(GlTest, AoHashMatchesCppOnEveryBit) {
  std::vector<glm::vec4> input;
  for (uint32_t i = 0; i < 64 * 64; ++i) {
    const uint32_t pixel = i < 2048 ? i : (i * 2654435761u) >> 8;  // small and scattered pixel indices
    input.emplace_back(float(pixel), float(i % 97), 0.0f, 0.0f);
  }
  const std::vector<glm::vec4> gpu = runKernel("TEST_AO_HASH", {input}, 64);
  for (size_t i = 0; i < input.size(); ++i) {
    const uint32_t pixel = uint32_t(input[i].x), sample = uint32_t(input[i].y);
    const uint32_t h = pcgHash(pixel ^ pcgHash(sample));
    const glm::vec2 u = aoRandom(pixel, sample);
    ASSERT_EQ(gpu[i].x, float(h >> 8)) << "pixel " << pixel << " sample " << sample;
    ASSERT_EQ(gpu[i].y, float(h & 255u)) << "pixel " << pixel << " sample " << sample;
    ASSERT_EQ(gpu[i].z, u.x);
    ASSERT_EQ(gpu[i].w, u.y);
  }
}

TEST_F(GlTest, AoDirectionMatchesCppAndIsCosineAboutTheNormal) {
  std::vector<glm::vec4> normals, randoms;
  for (uint32_t i = 0; i < 32 * 32; ++i) {
    const glm::vec2 a = aoRandom(i, 1000u), u = aoRandom(i, 7u);
    const float z = 2.0f * a.x - 1.0f, phi = 6.2831853f * a.y, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    glm::vec3 n(r * std::cos(phi), r * std::sin(phi), z);
    if (i < 4) n = glm::vec3(0.0f, 0.0f, i % 2 ? 1.0f : -1.0f);  // the frame's poles
    normals.emplace_back(n, 0.0f);
    randoms.emplace_back(u, 0.0f, 0.0f);
  }
  const std::vector<glm::vec4> gpu = runKernel("TEST_AO_DIRECTION", {normals, randoms}, 32);
  double meanCos = 0;
  for (size_t i = 0; i < normals.size(); ++i) {
    const glm::vec3 n(normals[i]), d = aoDirection(n, glm::vec2(randoms[i]));
    EXPECT_NEAR(gpu[i].x, d.x, 1e-5f) << i;
    EXPECT_NEAR(gpu[i].y, d.y, 1e-5f) << i;
    EXPECT_NEAR(gpu[i].z, d.z, 1e-5f) << i;
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-4f);
    EXPECT_GE(glm::dot(d, n), -1e-5f);
    meanCos += glm::dot(d, n) / double(normals.size());
  }
  EXPECT_NEAR(meanCos, 2.0 / 3.0, 0.03);  // E[cos] of a cosine-distributed hemisphere
}

struct Images {
  std::vector<float> cpu, gpu;
};

Images renderBoth(const Scene& scene, const ShadingConfig& shading, int size, int bounces) {
  const auto cpuStructure = makeCpuStructure("kd-restart", scene.triangles);
  const auto streamStructure = makeStreamStructure("kd-restart", scene.triangles);
  CpuRenderer cpu(scene, *cpuStructure, 0, shading);
  GpuRenderer gpu(scene, *streamStructure, size, size, 0, shading);
  return {cpu.render(scene.camera, size, size, bounces, false).rgb, gpu.render(scene.camera, bounces, false).rgb};
}

// Mean over pixels and channels of |a - b|, both clamped to [0, 1] as an image writes them.
double meanDifference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) sum += std::abs(std::clamp(a[i], 0.0f, 1.0f) - std::clamp(b[i], 0.0f, 1.0f));
  return sum / double(a.size());
}

TEST_F(GlTest, AoImagesOfBothRenderersAgreeWithinOneStep) {
  const Scene scene = loadScene("cornell");
  ShadingConfig shading;
  shading.mode = ShadingMode::Ao;
  const Images images = renderBoth(scene, shading, 64, 3);
  const double difference = meanDifference(images.cpu, images.gpu);
  EXPECT_LT(difference, 1.0 / 255.0);
  // Not trivially grey: corners are occluded, open walls are not.
  const auto [lo, hi] = std::minmax_element(images.cpu.begin(), images.cpu.end());
  EXPECT_LT(*lo, 0.6f);
  EXPECT_GT(*hi, 0.95f);
  RecordProperty("ao_mean_difference", std::to_string(difference));
}

// A glass sphere in front of a red wall, seen head on.
Scene glassSphereScene(float transmission) {
  Scene scene;
  scene.name = "glass sphere";
  scene.triangles = testmesh::uvSphere(24, 48, glm::vec3(0.0f), 1.0f);
  const size_t sphere = scene.triangles.size();
  for (Triangle t : testmesh::flatGrid(4, 4, 2, 0.0f)) {
    for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v = glm::vec3(8.0f * v->x - 4.0f, 8.0f * v->y - 4.0f, -3.0f);
    scene.triangles.push_back(t);
  }
  Material glass;
  glass.diffuse = glm::vec3(0.8f);
  glass.specular = glm::vec3(0.5f);
  glass.shininess = 40.0f;
  glass.transmission = transmission;
  glass.ior = 1.5f;
  Material wall;
  wall.diffuse = glm::vec3(0.9f, 0.1f, 0.1f);
  scene.materials = {glass, wall};
  scene.materialIds.assign(scene.triangles.size(), 1u);
  std::fill(scene.materialIds.begin(), scene.materialIds.begin() + ptrdiff_t(sphere), 0u);
  // The light off the axis: its highlight and the sphere's shadow fall off the centre pixel.
  scene.light = PointLight{glm::vec3(3.0f, 3.0f, 2.0f), glm::vec3(1.0f)};
  scene.background = glm::vec3(0.0f, 0.0f, 0.3f);
  scene.camera = CameraSpec{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 45.0f};
  return scene;
}

TEST_F(GlTest, WhittedImagesAgreeAndGlassShowsTheWallBehind) {
  constexpr int kSize = 48;
  ShadingConfig shading;
  shading.mode = ShadingMode::Whitted;
  const Images glass = renderBoth(glassSphereScene(1.0f), shading, kSize, 6);
  // Tolerance: 2/255 mean; silhouettes and the refracted rays' grazing
  // branches may differ in single pixels between the two float pipelines.
  EXPECT_LT(meanDifference(glass.cpu, glass.gpu), 2.0 / 255.0);
  const Images opaque = renderBoth(glassSphereScene(0.0f), shading, kSize, 6);
  EXPECT_LT(meanDifference(opaque.cpu, opaque.gpu), 2.0 / 255.0);
  // The centre pixel looks through the sphere: red wall behind glass, grey opaque sphere.
  const size_t centre = 3 * (size_t(kSize / 2) * kSize + kSize / 2);
  for (const std::vector<float>* rgb : {&glass.cpu, &glass.gpu}) {
    EXPECT_GT((*rgb)[centre], 0.3f);
    EXPECT_GT((*rgb)[centre], 3.0f * (*rgb)[centre + 1]) << "the wall's red through the glass";
  }
  for (const std::vector<float>* rgb : {&opaque.cpu, &opaque.gpu})
    EXPECT_NEAR((*rgb)[centre], (*rgb)[centre + 1], 0.05f) << "an opaque grey sphere";
  EXPECT_GT(meanDifference(glass.cpu, opaque.cpu), 0.02);
}

TEST_F(GlTest, WhittedShadowRaysGoToEveryLight) {
  constexpr int kSize = 32;
  ShadingConfig shading;
  shading.mode = ShadingMode::Whitted;
  Scene one = glassSphereScene(0.0f);
  Scene two = one;
  // Scene::light stays the first light; Scene::lights lists both (as the AFF loader fills them).
  two.lights = {one.light, PointLight{glm::vec3(-3.0f, -2.0f, 3.0f), glm::vec3(0.5f, 0.5f, 1.0f)}};
  const Images a = renderBoth(one, shading, kSize, 3), b = renderBoth(two, shading, kSize, 3);
  EXPECT_LT(meanDifference(b.cpu, b.gpu), 2.0 / 255.0);
  // Every pixel gains the second light's term or keeps what it had; many gain.
  int brighter = 0;
  for (size_t i = 0; i < a.cpu.size(); ++i) {
    EXPECT_GE(b.cpu[i], a.cpu[i] - 1e-5f) << i;
    brighter += b.cpu[i] > a.cpu[i] + 0.01f;
  }
  EXPECT_GT(brighter, kSize * kSize / 4);
}

TEST_F(GlTest, ThesisShadingIsTheDefaultConfig) {
  const Scene scene = loadScene("cornell");
  const auto cpuStructure = makeCpuStructure("kd-restart", scene.triangles);
  CpuRenderer byDefault(scene, *cpuStructure, 0), thesis(scene, *cpuStructure, 0, ShadingConfig{});
  EXPECT_EQ(byDefault.render(scene.camera, 24, 24, 3, false).rgb, thesis.render(scene.camera, 24, 24, 3, false).rgb);
  EXPECT_EQ(ShadingConfig{}.mode, ShadingMode::Thesis);
}

}  // namespace
}  // namespace passtrace
