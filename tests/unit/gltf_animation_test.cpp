// glTF animations evaluated at --time (scenes/gltf_animation.h): each
// interpolation against values computed here by hand, morph targets, the
// animation range and the static/moving marks (tests/data/gltf/make_gltf.py
// documents the files).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "scenes/gltf_loader.h"
#include "scenes/scene_error.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
const fs::path kData = fs::path(PASSTRACE_TEST_DATA) / "gltf";

// The file's triangle (0,0,0) (1,0,0) (0,1,0) after p -> f(p).
template <typename F>
void expectTriangle(const Triangle& t, F f, const std::string& what) {
  const glm::vec3 expected[3] = {f(glm::vec3(0, 0, 0)), f(glm::vec3(1, 0, 0)), f(glm::vec3(0, 1, 0))};
  const glm::vec3 got[3] = {t.v0, t.v1, t.v2};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[k][c], expected[k][c], 1e-5f) << what << " corner " << k << " axis " << c;
}

TEST(GltfAnimation, EachInterpolationAtKeysBetweenAndBeyond) {
  for (const float t : {-1.0f, 0.0f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const Scene s = loadGltf(kData / "animated.gltf", t);
    ASSERT_EQ(s.triangles.size(), 4u);
    const float u = std::clamp(t / 2.0f, 0.0f, 1.0f);  // the keys span [0, 2]
    expectTriangle(s.triangles[0], [](glm::vec3 p) { return p; }, "static");
    // LINEAR translation 0 -> 4 in x.
    expectTriangle(s.triangles[1], [&](glm::vec3 p) { return p + glm::vec3(4.0f * u, 0, 0); }, "linear");
    // STEP: the key at t = 1 (90 degrees about z) from t = 1 on.
    expectTriangle(s.triangles[2], [&](glm::vec3 p) { return t >= 1.0f ? glm::vec3(-p.y, p.x, p.z) : p; }, "step");
    // CUBICSPLINE with zero tangents: 1 + 2 (3u^2 - 2u^3).
    const float scale = 1.0f + 2.0f * (3 * u * u - 2 * u * u * u);
    expectTriangle(s.triangles[3], [&](glm::vec3 p) { return p * scale; }, "cubic");
  }
}

TEST(GltfAnimation, RangeAndMovingMarks) {
  const Scene s = loadGltf(kData / "animated.gltf", 0.0f);
  ASSERT_TRUE(s.animation.has_value());
  EXPECT_EQ(s.animation->start, 0.0f);
  EXPECT_EQ(s.animation->end, 2.0f);
  EXPECT_EQ(s.moving, (std::vector<uint8_t>{0, 1, 1, 1}));
  // A still file: no range, nothing moving.
  const Scene still = loadGltf(kData / "hierarchy.gltf", 0.0f);
  EXPECT_FALSE(still.animation.has_value());
  EXPECT_TRUE(still.moving.empty());
}

TEST(GltfAnimation, MorphTargetWeights) {
  for (const float t : {0.0f, 0.25f, 1.0f}) {
    const Scene s = loadGltf(kData / "morph.gltf", t);
    ASSERT_EQ(s.triangles.size(), 2u);
    for (const Triangle& tri : s.triangles)
      for (const glm::vec3& v : {tri.v0, tri.v1, tri.v2}) EXPECT_NEAR(v.z, t, 1e-6f) << "t = " << t;
    EXPECT_EQ(s.moving, (std::vector<uint8_t>{1, 1}));
  }
}

TEST(GltfAnimation, NonFiniteTimeIsAnError) {
  EXPECT_THROW(loadGltf(kData / "animated.gltf", NAN), SceneError);
}

}  // namespace
}  // namespace passtrace
