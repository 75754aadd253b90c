// The Cows-like benchmark scene built in code.

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "scenes/cows_scene.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

TEST(CowsScene, TriangleCountIsPinnedAndInRange) {
  const Scene scene = makeCowsScene();
  EXPECT_EQ(scene.name, "cows");
  const bool bunny = fs::exists("/usr/share/glmark2/models/bunny.obj");
  EXPECT_EQ(scene.triangles.size(), bunny ? kCowsTriangles : kCowsTrianglesNoBunny);
  EXPECT_GE(scene.triangles.size(), 20000u);
  EXPECT_LE(scene.triangles.size(), 40000u);
  EXPECT_EQ(scene.materialIds.size(), scene.triangles.size());
  EXPECT_EQ(scene.vertexNormals.size(), scene.triangles.size());
}

TEST(CowsScene, FallsBackToABlobWithoutTheBunny) {
  const Scene scene = makeCowsScene("/nonexistent/bunny.obj");
  EXPECT_EQ(scene.name, "cows");
  EXPECT_EQ(scene.triangles.size(), kCowsTrianglesNoBunny);
  EXPECT_GE(scene.triangles.size(), 20000u);
  EXPECT_EQ(scene.vertexNormals.size(), scene.triangles.size());
}

TEST(CowsScene, IsDeterministic) {
  const Scene a = makeCowsScene();
  const Scene b = loadScene("cows");
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    ASSERT_EQ(a.triangles[i].v0, b.triangles[i].v0) << i;
    ASSERT_EQ(a.triangles[i].v1, b.triangles[i].v1) << i;
    ASSERT_EQ(a.triangles[i].v2, b.triangles[i].v2) << i;
    ASSERT_EQ(a.materialIds[i], b.materialIds[i]) << i;
  }
}

TEST(CowsScene, GroundMirrorTreeAndMeshes) {
  const Scene scene = makeCowsScene();
  // Exactly one mirror material, on the back plane (triangles 2 and 3).
  std::size_t mirrors = 0;
  for (const Material& m : scene.materials) mirrors += m.isMirror() ? 1 : 0;
  EXPECT_EQ(mirrors, 1u);
  EXPECT_TRUE(scene.materials[scene.materialIds[2]].isMirror());
  EXPECT_TRUE(scene.materials[scene.materialIds[3]].isMirror());
  EXPECT_FALSE(scene.materials[scene.materialIds[0]].isMirror());
  for (std::size_t i = 4; i < scene.triangles.size(); ++i) ASSERT_FALSE(scene.materials[scene.materialIds[i]].isMirror());
  // The tree: big triangles at the bottom, small ones up top.
  float bottomArea = 0.0f, topArea = 1e30f;
  std::size_t treeTriangles = 0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.materialIds[i] != 2 && scene.materialIds[i] != 3) continue;
    ++treeTriangles;
    const Triangle& t = scene.triangles[i];
    const float area = 0.5f * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
    const float y = (t.v0.y + t.v1.y + t.v2.y) / 3.0f;
    if (y < 1.5f) bottomArea = std::max(bottomArea, area);
    if (y > 6.0f && area > 0.0f) topArea = std::min(topArea, area);
  }
  EXPECT_GT(treeTriangles, 10000u);
  EXPECT_GT(bottomArea, 100.0f * topArea);
  // Everything stands on or above the ground.
  const Aabb box = scene.bounds();
  EXPECT_GE(box.min.y, -1e-4f);
  for (const auto& normals : scene.vertexNormals)
    for (const glm::vec3& n : normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
  // The view looks at the scene from the front.
  EXPECT_GT(scene.camera.eye.z, box.max.z);
  EXPECT_GT(scene.light.position.y, box.max.y);
}

}  // namespace
}  // namespace passtrace
