// --export: every built-in scene, written as OBJ, glTF and GLB, loads back
// with the same triangles (bit for bit) in the same order, the same vertex
// normals, and the same material on every triangle as far as the format holds
// materials (scenes/scene_export.h); an unknown format is a one-line error.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "render/output_files.h"
#include "scenes/scene_export.h"
#include "scenes/scene_registry.h"
#include "scenes/tessellate.h"
#include "tests/bart_dir.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

class SceneExport : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("passtrace_export_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

bool sameVec(glm::vec3 a, glm::vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// glTF holds unit normals: the export's are the scene's normalized, within a
// few ulps after the loader normalizes them again.
bool sameNormal(glm::vec3 original, glm::vec3 loaded, const Triangle& t, bool unit) {
  if (!unit) return sameVec(original, loaded);
  const float length = glm::length(original);
  const glm::vec3 expected = length > 0.0f ? original / length : faceNormal(t);
  return glm::length(expected - loaded) <= 1e-6f;
}

void expectSameScene(const Scene& original, const Scene& loaded, bool obj) {
  const bool mirrorsKeepTheirOwnColour = obj, unitNormals = !obj;
  ASSERT_EQ(loaded.triangles.size(), original.triangles.size());
  size_t differentTriangles = 0, differentNormals = 0, differentMaterials = 0;
  for (size_t i = 0; i < original.triangles.size(); ++i) {
    const Triangle& a = original.triangles[i];
    const Triangle& b = loaded.triangles[i];
    if (!sameVec(a.v0, b.v0) || !sameVec(a.v1, b.v1) || !sameVec(a.v2, b.v2)) ++differentTriangles;
    if (original.hasVertexNormals())
      for (int k = 0; k < 3; ++k)
        if (!sameNormal(original.vertexNormals[i][k], loaded.vertexNormals[i][k], a, unitNormals)) ++differentNormals;
    const Material& m = original.materials[original.materialIds[i]];
    const Material& n = loaded.materials[loaded.materialIds[i]];
    const bool same = m.isMirror() == n.isMirror() &&
                      (m.isMirror() ? sameVec(m.mirror, n.mirror) &&
                                          (!mirrorsKeepTheirOwnColour || sameVec(m.diffuse, n.diffuse))
                                    : sameVec(m.diffuse, n.diffuse));
    differentMaterials += !same;
  }
  EXPECT_EQ(differentTriangles, 0u);
  EXPECT_EQ(loaded.hasVertexNormals(), original.hasVertexNormals());
  EXPECT_EQ(differentNormals, 0u);
  EXPECT_EQ(differentMaterials, 0u);
}

TEST_P(SceneExport, ReloadsWithTheSameTrianglesInTheSameOrder) {
  SceneOptions options;
  options.triangles = 20000;  // the procedural scene, small
  options.bartDir = test::bartDir();
  Scene scene;
  try {
    scene = loadScene(GetParam(), options);
  } catch (const std::exception& e) {
    GTEST_SKIP() << GetParam() << " is not available here: " << e.what();
  }
  for (const char* ext : {".obj", ".gltf", ".glb"}) {
    SCOPED_TRACE(GetParam() + ext);
    const fs::path file = dir_ / ext / (GetParam() + ext);
    fs::create_directories(file.parent_path());
    OutputFiles outputs;
    for (const ExportedFile& f : exportFiles(scene, file)) outputs.write(f.path, f.bytes);
    outputs.commitAll();
    // Only the export (and OBJ's material library) is left behind.
    for (const auto& entry : fs::directory_iterator(file.parent_path()))
      EXPECT_TRUE(entry.path() == file || entry.path().extension() == ".mtl") << entry.path();
    const Scene loaded = loadScene(file.string(), options);
    // glTF's mirror is its base colour: a mirror's diffuse colour is not kept.
    expectSameScene(scene, loaded, std::string(ext) == ".obj");
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, SceneExport,
                         ::testing::Values("cows", "robots", "kitchen", "bunny", "cornell", "spheres"),
                         [](const auto& info) { return info.param; });

// Writing the files is OutputFiles' (tests/unit/output_files_test.cpp).
TEST_F(SceneExport, UnknownFormatIsAOneLineError) {
  const Scene scene = loadScene("cornell");
  try {
    exportFiles(scene, dir_ / "x.ply");
    ADD_FAILURE() << "no error for .ply";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.ply: cannot export: unknown format '.ply'"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(isExportFormat("a.OBJ"));
  EXPECT_FALSE(isExportFormat("a.ply"));
}

}  // namespace
}  // namespace passtrace
