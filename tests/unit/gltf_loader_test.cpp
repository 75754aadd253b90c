// The glTF 2.0 loader on small files written by tests/data/gltf/make_gltf.py.

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scenes/gltf_loader.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

const fs::path kGltfData = fs::path(PASSTRACE_TEST_DATA) / "gltf";

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expectTriangle(const Triangle& t, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  expectNear(t.v0, a);
  expectNear(t.v1, b);
  expectNear(t.v2, c);
}

std::string gltfError(const std::string& name) {
  try {
    loadGltf(kGltfData / name);
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for " << name;
  return {};
}

// glTF has no lines: "FILE: reason".
void expectError(const std::string& name, const std::string& part) {
  const std::string message = gltfError(name);
  const std::string prefix = (kGltfData / name).string() + ": ";
  EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
  EXPECT_NE(message.find(part), std::string::npos) << "\"" << message << "\" lacks \"" << part << "\"";
}

TEST(GltfLoader, NodeHierarchyWithTrsAndMatrix) {
  const Scene scene = loadGltf(kGltfData / "hierarchy.gltf");
  EXPECT_EQ(scene.name, "hierarchy");
  ASSERT_EQ(scene.triangles.size(), 2u);
  // translate (10, 0, 0) * rotate 90 about z * scale 2
  expectTriangle(scene.triangles[0], {10, 0, 0}, {10, 2, 0}, {8, 0, 0});
  // matrix: translate (0, 0, -5)
  expectTriangle(scene.triangles[1], {0, 0, -5}, {1, 0, -5}, {0, 1, -5});
  EXPECT_TRUE(scene.vertexNormals.empty());
  EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{0, 0}));
  ASSERT_EQ(scene.materials.size(), 1u);
  // No camera or light: framed on the bounds.
  expectNear(scene.camera.lookAt, scene.bounds().center());
  EXPECT_GT(scene.light.position.y, scene.bounds().max.y);
}

TEST(GltfLoader, StripsFansAndNonIndexedTrianglesAndSkippedPrimitives) {
  testing::internal::CaptureStderr();
  const Scene scene = loadGltf(kGltfData / "modes.gltf");
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(warnings, (kGltfData / "modes.gltf").string() + ": skipped 2 non-triangle primitives\n");
  ASSERT_EQ(scene.triangles.size(), 3u + 4u + 2u);
  // Strip (spec): (0 1 2), (1 3 2), (2 3 4).
  expectTriangle(scene.triangles[0], {0, 0, 0}, {0, 1, 0}, {1, 0, 0});
  expectTriangle(scene.triangles[1], {0, 1, 0}, {1, 1, 0}, {1, 0, 0});
  expectTriangle(scene.triangles[2], {1, 0, 0}, {1, 1, 0}, {2, 0, 0});
  // Fan (spec): (i+1, i+2, 0).
  expectTriangle(scene.triangles[3], {1, 0, 1}, {1, 1, 1}, {0, 0, 1});
  expectTriangle(scene.triangles[6], {-1, 1, 1}, {-1, 0, 1}, {0, 0, 1});
  // Non-indexed triangles.
  expectTriangle(scene.triangles[7], {0, 0, 2}, {1, 0, 2}, {0, 1, 2});
  expectTriangle(scene.triangles[8], {0, 0, 3}, {1, 0, 3}, {0, 1, 3});
}

TEST(GltfLoader, CameraLightMaterialsAndNormals) {
  const Scene scene = loadGltf(kGltfData / "view.gltf");
  ASSERT_EQ(scene.triangles.size(), 2u);
  expectNear(scene.camera.eye, {0, 1, 5});
  expectNear(scene.camera.lookAt, {0, 1, 4});
  expectNear(scene.camera.up, {0, 1, 0});
  EXPECT_NEAR(scene.camera.fovDegrees, 0.5f * 180.0f / 3.14159265f, 1e-4f);
  // The first point light (the directional one is passed over), colour only.
  expectNear(scene.light.position, {2, 3, 4});
  expectNear(scene.light.color, {1.0f, 0.5f, 0.25f});
  // Metallic 1, roughness 0.05: a mirror reflecting baseColor.
  const Material& mirror = scene.materials[scene.materialIds[0]];
  EXPECT_TRUE(mirror.isMirror());
  expectNear(mirror.mirror, {0.9f, 0.8f, 0.7f});
  const Material& diffuse = scene.materials[scene.materialIds[1]];
  EXPECT_FALSE(diffuse.isMirror());
  expectNear(diffuse.diffuse, {0.2f, 0.4f, 0.6f});
  // --shading whitted's terms from KHR_materials_transmission, _ior and _specular (roughness 0.5: 2/0.25 - 2).
  EXPECT_FLOAT_EQ(diffuse.transmission, 0.75f);
  EXPECT_FLOAT_EQ(diffuse.ior, 1.33f);
  expectNear(diffuse.specular, {0.5f, 0.25f, 0.125f});
  EXPECT_FLOAT_EQ(diffuse.shininess, 6.0f);
  // Without the extensions: opaque, glTF's default ior 1.5, no highlight.
  EXPECT_EQ(mirror.transmission, 0.0f);
  EXPECT_EQ(mirror.ior, 1.5f);
  expectNear(mirror.specular, {0, 0, 0});
  // Normals through the inverse transpose of scale (2, 1, 1).
  ASSERT_EQ(scene.vertexNormals.size(), 2u);
  expectNear(scene.vertexNormals[0][0], glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f)));
  expectTriangle(scene.triangles[0], {0, 0, 0}, {2, 0, 0}, {0, 1, 0});
  // Without NORMAL: the geometric normal.
  expectNear(scene.vertexNormals[1][2], {0, 0, 1});
}

TEST(GltfLoader, BinaryGlbThroughTheRegistry) {
  const Scene scene = loadScene((kGltfData / "binary.glb").string());
  EXPECT_EQ(scene.name, "binary");
  ASSERT_EQ(scene.triangles.size(), 2u);
  expectTriangle(scene.triangles[0], {0, 0, 1}, {1, 0, 1}, {1, 1, 1});
  expectTriangle(scene.triangles[1], {0, 0, 1}, {1, 1, 1}, {0, 1, 1});
  EXPECT_EQ(loadScene((kGltfData / "modes.gltf").string()).triangles.size(), 9u);
}

TEST(GltfLoaderErrors, IndexOutOfRange) {
  expectError("index_out_of_range.gltf", "mesh 0 primitive 0: index 99 out of range (3 vertices)");
}
TEST(GltfLoaderErrors, WrongCount) {
  expectError("not_multiple_of_3.gltf", "mesh 0 primitive 0: TRIANGLES with 4 indices, not a multiple of 3");
}
TEST(GltfLoaderErrors, NaNPosition) { expectError("nan_position.gltf", "mesh 0 primitive 0: accessor 0 element 1 is not finite"); }
TEST(GltfLoaderErrors, LightColorOverflowsSinglePrecision) {
  expectError("light_overflow.gltf", "node 1: light 0: color is not finite in single precision");
}
TEST(GltfLoaderErrors, AccessorLargerThanItsBuffer) { expectError("accessor_overflow.gltf", "accessor 0"); }
TEST(GltfLoaderErrors, NodeCycle) { expectError("node_cycle.gltf", "node 0 has more than one parent (or a cycle)"); }
TEST(GltfLoaderErrors, MissingBufferFile) { expectError("missing_buffer.gltf", "missing.bin"); }
TEST(GltfLoaderErrors, BadJson) { expectError("bad_json.gltf", ""); }
TEST(GltfLoaderErrors, TruncatedGlb) { expectError("truncated.glb", ""); }
TEST(GltfLoaderErrors, MissingFile) { expectError("nothing_here.gltf", "cannot open: "); }

}  // namespace
}  // namespace passtrace
