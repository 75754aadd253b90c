// PLY and OFF (passtrace's own readers) and the formats read through Assimp
// on small files written by tests/data/ply/make_ply.py.

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scenes/obj_loader.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

const fs::path kPlyData = fs::path(PASSTRACE_TEST_DATA) / "ply";

// The corners of t starting at its smallest one (x, then y, then z), winding
// kept: Assimp may start a triangle at another corner than the file does.
std::array<glm::vec3, 3> canonical(const Triangle& t) {
  std::array<glm::vec3, 3> c = {t.v0, t.v1, t.v2};
  const auto less = [](const glm::vec3& a, const glm::vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::rotate(c.begin(), std::min_element(c.begin(), c.end(), less), c.end());
  return c;
}

void expectSameTriangles(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i)
    EXPECT_EQ(canonical(a.triangles[i]), canonical(b.triangles[i])) << "triangle " << i;
}

std::string loadError(const std::string& name) {
  try {
    loadScene((kPlyData / name).string());
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for " << name;
  return {};
}

// "FILE: reason", or "FILE:LINE: reason" where the line is given.
void expectError(const std::string& name, const std::string& part, int line = 0) {
  const std::string message = loadError(name);
  std::string prefix = (kPlyData / name).string();
  if (line > 0) prefix += ':' + std::to_string(line);
  prefix += ": ";
  EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
  EXPECT_NE(message.find(part), std::string::npos) << "\"" << message << "\" lacks \"" << part << "\"";
}

TEST(PlyLoader, AsciiQuadsBecomeTwoTrianglesEach) {
  const Scene scene = loadScene((kPlyData / "cube.ply").string());
  EXPECT_EQ(scene.name, "cube");
  ASSERT_EQ(scene.triangles.size(), 12u);
  // The first quad (0 3 2 1) as the OBJ loader's fan: (0 3 2), (0 2 1).
  EXPECT_EQ(canonical(scene.triangles[0]), canonical(Triangle{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
  EXPECT_EQ(canonical(scene.triangles[1]), canonical(Triangle{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}}));
  EXPECT_EQ(scene.bounds().min, glm::vec3(0.0f));
  EXPECT_EQ(scene.bounds().max, glm::vec3(1.0f));
  // No materials in PLY: the OBJ loader's default; no normals in the file.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].diffuse, Material{}.diffuse);
  EXPECT_EQ(scene.materialIds, std::vector<uint32_t>(12, 0));
  EXPECT_TRUE(scene.vertexNormals.empty());
  // Framed on the bounds, as OBJ scenes are.
  EXPECT_EQ(scene.camera.lookAt, glm::vec3(0.5f));
}

TEST(PlyLoader, BinaryLittleEndianInTheBunnyLayout) {
  const Scene scene = loadScene((kPlyData / "pyramid_binary.ply").string());
  EXPECT_EQ(scene.name, "pyramid_binary");
  ASSERT_EQ(scene.triangles.size(), 6u);  // one quad and four triangles
  EXPECT_EQ(canonical(scene.triangles[2]), canonical(Triangle{{0, 0, 0}, {0.5f, 1, 0.5f}, {1, 0, 0}}));
  EXPECT_EQ(scene.bounds().max, glm::vec3(1.0f));
}

TEST(PlyLoader, SameTrianglesAsTheObjFile) {
  expectSameTriangles(loadObj(kPlyData / "cube.obj"), loadScene((kPlyData / "cube.ply").string()));
  expectSameTriangles(loadObj(kPlyData / "pyramid.obj"), loadScene((kPlyData / "pyramid_binary.ply").string()));
}

// The other formats Assimp reads, each holding the pyramid.
TEST(PlyLoader, OtherFormatsThroughAssimp) {
  const Scene reference = loadObj(kPlyData / "pyramid.obj");
  for (const char* name : {"pyramid.stl", "pyramid.off", "pyramid.dae", "pyramid.3ds", "pyramid.x", "pyramid.fbx"}) {
    SCOPED_TRACE(name);
    const Scene scene = loadScene((kPlyData / name).string());
    ASSERT_EQ(scene.triangles.size(), 6u);
    // The extent only: Assimp's 3DS export turns y up into z up (a rotation
    // node), which its 3DS import keeps.
    EXPECT_EQ(scene.bounds().max - scene.bounds().min, glm::vec3(1.0f));
  }
  expectSameTriangles(reference, loadScene((kPlyData / "pyramid.stl").string()));
  expectSameTriangles(reference, loadScene((kPlyData / "pyramid.off").string()));
}

// The Stanford bunny's original file (bunny/reconstruction/bun_zipper.ply of
// the Stanford repository: 35947 vertices, 69451 triangles) where a copy
// exists; no Debian package ships it.
TEST(PlyLoader, StanfordBunnyWhenPresent) {
  const char* env = std::getenv("PASSTRACE_BUNNY_PLY");
  const fs::path bunny = env != nullptr ? fs::path(env) : fs::path("/usr/share/passtrace/bun_zipper.ply");
  if (!fs::exists(bunny)) GTEST_SKIP() << bunny << " not found (set PASSTRACE_BUNNY_PLY to bun_zipper.ply)";
  EXPECT_EQ(loadScene(bunny.string()).triangles.size(), 69451u);
}

TEST(PlyLoaderErrors, TruncatedBinaryBody) { expectError("truncated_binary.ply", "binary body ends inside face 4 of 5"); }

TEST(PlyLoaderErrors, FaceIndexOutOfRange) { expectError("index_out_of_range.ply", "face 1 names vertex 99 of 5", 17); }

// A face naming a vertex the file lacks, in every format with indices: a
// one-line error, whether Assimp rejects it (COLLADA), clamps it (3DS; OFF
// before passtrace read OFF itself) or drops it (X: from its face; FBX: the
// whole mesh). STL stores corners, not indices.
TEST(PlyLoaderErrors, IndexOutOfRangeInEveryIndexedFormat) {
  expectError("index_out_of_range.off", "face 0 names vertex 7 of 3", 6);
  expectError("index_out_of_range.dae", "Invalid data index (99/16)");
  expectError("index_out_of_range.3ds", "3DS: Vertex index overflow");
  expectError("index_out_of_range.x", "mesh 0 face 4 has 2 corners: a face names a vertex out of range");
  expectError("index_out_of_range.fbx", "polygon vertex index out of range");
}

TEST(PlyLoaderErrors, ElementCountLargerThanTheBody) {
  expectError("count_too_large.ply", "element 'vertex' declares 4000000000 instances", 4);
}

TEST(PlyLoaderErrors, AsciiListLongerThanItsLine) {
  expectError("ascii_list_too_long.ply", "face 0: '4000000000' does not fit a uchar", 14);
}

TEST(PlyLoaderErrors, NonFiniteVertices) {
  expectError("nan_vertex.ply", "vertex 1 is not finite", 12);
  expectError("inf_vertex_binary.ply", "vertex 1 is not finite");
}

TEST(PlyLoaderErrors, Garbage) {
  expectError("garbage.ply", "unknown header keyword 'this'", 2);
  expectError("not_ply.ply", "not a PLY file", 1);
  expectError("bad_type.ply", "unknown property type 'real'", 6);
}

TEST(PlyLoaderErrors, PointsOnly) { expectError("points_only.ply", "no triangles"); }

TEST(PlyLoaderErrors, MissingFileAndDirectory) {
  expectError("missing.ply", "cannot open");
  const fs::path dir = fs::temp_directory_path() / "passtrace_ply_dir.ply";
  fs::create_directories(dir);
  try {
    loadScene(dir.string());
    ADD_FAILURE() << "a directory loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": cannot open: not a regular file");
  }
  fs::remove(dir);
}

}  // namespace
}  // namespace passtrace
