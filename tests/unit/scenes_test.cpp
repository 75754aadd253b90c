// The OBJ loader, the Cornell box and the scene registry.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scenes/cornell_box.h"
#include "scenes/obj_loader.h"
#include "scenes/one_line_message.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

const fs::path kObjData = fs::path(PASSTRACE_TEST_DATA) / "obj";
const fs::path kBunny = "/usr/share/glmark2/models/bunny.obj";

void expectVec3(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_EQ(actual.x, expected.x);
  EXPECT_EQ(actual.y, expected.y);
  EXPECT_EQ(actual.z, expected.z);
}

void expectTriangle(const Triangle& t, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  expectVec3(t.v0, a);
  expectVec3(t.v1, b);
  expectVec3(t.v2, c);
}

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "\"" << text << "\" lacks \"" << part << "\"";
}

// The message of the SceneError that loading throws, or a test failure.
template <class Load>
std::string errorOf(Load&& load) {
  try {
    load();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no SceneError thrown";
  return {};
}

std::string objError(const fs::path& path) {
  return errorOf([&] { loadObj(path); });
}

// A fresh directory for files written by a test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* test = testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("passtrace-" + std::string(test->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& contents) const {
    const fs::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << contents;
    return file;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// --- loading ------------------------------------------------------------------

TEST(ObjLoader, FanTriangulatesInFileOrder) {
  const Scene scene = loadObj(kObjData / "quad_pentagon.obj");
  EXPECT_EQ(scene.name, "quad_pentagon");
  ASSERT_EQ(scene.triangles.size(), 5u);
  const glm::vec3 v[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0},
                         {3, 0, 0}, {3.5f, 1, 0}, {2.5f, 2, 0}, {1.5f, 1, 0}};
  expectTriangle(scene.triangles[0], v[0], v[1], v[2]);
  expectTriangle(scene.triangles[1], v[0], v[2], v[3]);
  expectTriangle(scene.triangles[2], v[4], v[5], v[6]);
  expectTriangle(scene.triangles[3], v[4], v[6], v[7]);
  expectTriangle(scene.triangles[4], v[4], v[7], v[8]);
  EXPECT_FALSE(scene.hasVertexNormals());
  ASSERT_EQ(scene.materials.size(), 1u);
  expectVec3(scene.materials[0].diffuse, glm::vec3(0.8f));
  EXPECT_FALSE(scene.materials[0].isMirror());
  EXPECT_EQ(scene.materialIds, std::vector<uint32_t>(5, 0));
}

TEST(ObjLoader, ReadsVertexNormals) {
  const Scene scene = loadObj(kObjData / "normals.obj");
  ASSERT_EQ(scene.triangles.size(), 2u);
  ASSERT_EQ(scene.vertexNormals.size(), 2u);
  expectVec3(scene.vertexNormals[0][0], {0, 0, 1});
  expectVec3(scene.vertexNormals[0][1], {0, 0.6f, 0.8f});
  expectVec3(scene.vertexNormals[0][2], {0.6f, 0, 0.8f});
  expectVec3(scene.vertexNormals[1][0], {0, 0.6f, 0.8f});
  expectVec3(scene.vertexNormals[1][1], {0, 0, 1});
  expectVec3(scene.vertexNormals[1][2], {0.6f, 0, 0.8f});
}

TEST(ObjLoader, DropsNormalsUnlessEveryCornerHasOne) {
  const Scene scene = loadObj(kObjData / "some_normals.obj");
  EXPECT_EQ(scene.triangles.size(), 2u);
  EXPECT_FALSE(scene.hasVertexNormals());
}

TEST(ObjLoader, ResolvesNegativeIndices) {
  const Scene scene = loadObj(kObjData / "negative_indices.obj");
  ASSERT_EQ(scene.triangles.size(), 2u);
  expectTriangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  expectTriangle(scene.triangles[1], {0, 0, 0}, {0, 0, 1}, {0, 1, 0});
}

TEST(ObjLoader, MapsMtlMaterials) {
  const Scene scene = loadObj(kObjData / "materials.obj");
  ASSERT_EQ(scene.materials.size(), 3u);  // red, mirror, then the default
  expectVec3(scene.materials[0].diffuse, {0.9f, 0.1f, 0.1f});
  EXPECT_FALSE(scene.materials[0].isMirror());  // Ks without illum 3 is no mirror
  expectVec3(scene.materials[0].specular, glm::vec3(0.5f));  // --shading whitted's highlight
  EXPECT_EQ(scene.materials[0].transmission, 0.0f);  // no d: opaque
  EXPECT_EQ(scene.materials[0].ior, 1.0f);          // no Ni: tinyobjloader reads 1
  expectVec3(scene.materials[1].mirror, glm::vec3(0.95f));
  expectVec3(scene.materials[2].diffuse, glm::vec3(0.8f));
  EXPECT_EQ(scene.materialIds, (std::vector<uint32_t>{2, 0, 1}));
}

TEST(ObjLoader, CountsLinesLikeTinyObjLoader) {
  const TempDir dir;
  // Windows and old-Mac line ends; the bad number is on line 4 either way.
  const fs::path crlf = dir.write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\n\r\nv 0 x 0\r\nf 1 2 3\r\n");
  expectContains(objError(crlf), crlf.string() + ":4: ");
  const fs::path cr = dir.write("cr.obj", "v 0 0 0\rv 1 0 0\r\rv 0 x 0\rf 1 2 3\r");
  expectContains(objError(cr), cr.string() + ":4: ");
  // The last line needs no line end.
  EXPECT_EQ(loadObj(dir.write("last.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3")).triangles.size(), 1u);
}

TEST(ObjLoader, AcceptsCommonSyntax) {
  const TempDir dir;
  const Scene scene = loadObj(dir.write("syntax.obj",
                                        "# comment\n"
                                        "mtllib missing.mtl\n"  // a missing library means the default material
                                        "o thing\n"
                                        "v +1 -2.5e1 .5\n"
                                        "\tv 1.  0 0 1\n"  // leading tab, optional w
                                        "v 0 1 0 0.5 0.5 0.5\n"  // vertex colour
                                        "vt 0.5\n"
                                        "s off\n"
                                        "usemtl nowhere\n"
                                        "f 1/1 2/1 3/1  \n"));
  ASSERT_EQ(scene.triangles.size(), 1u);
  expectVec3(scene.triangles[0].v0, {1, -25, 0.5f});
  ASSERT_EQ(scene.materials.size(), 1u);
}

// --- bad input ------------------------------------------------------------------

TEST(ObjLoaderErrors, MissingFile) {
  const fs::path path = kObjData / "does_not_exist.obj";
  const std::string message = objError(path);
  expectContains(message, path.string() + ": cannot open: ");
  expectContains(message, "No such file or directory");
}

TEST(ObjLoaderErrors, BadNumber) {
  const fs::path path = kObjData / "bad_number.obj";
  expectContains(objError(path), path.string() + ":3: bad number 'zero'");
}

TEST(ObjLoaderErrors, NanVertex) {
  const fs::path path = kObjData / "nan_vertex.obj";
  expectContains(objError(path), path.string() + ":4: non-finite number 'nan'");
}

TEST(ObjLoaderErrors, IndexZero) {
  const fs::path path = kObjData / "index_zero.obj";
  expectContains(objError(path), path.string() + ":5: vertex index 0");
}

TEST(ObjLoaderErrors, IndexOutOfRange) {
  const fs::path path = kObjData / "index_out_of_range.obj";
  expectContains(objError(path), path.string() + ":6: vertex index 4 out of range (3 defined so far)");
}

TEST(ObjLoaderErrors, FaceWithTwoVertices) {
  const fs::path path = kObjData / "two_vertex_face.obj";
  expectContains(objError(path), path.string() + ":5: face needs at least 3 vertices, got 2");
}

TEST(ObjLoaderErrors, NoFaces) {
  const fs::path path = kObjData / "no_faces.obj";
  EXPECT_EQ(objError(path), path.string() + ": no triangles");
}

TEST(ObjLoaderErrors, EmptyFile) {
  const TempDir dir;
  const fs::path path = dir.write("empty.obj", "");
  EXPECT_EQ(objError(path), path.string() + ": no triangles");
}

TEST(ObjLoaderErrors, MoreLineErrors) {
  const TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const struct {
    const char* name;
    std::string contents;
    const char* expected;
  } cases[] = {
      {"short_vertex.obj", "v 0 0 0\nv 1 0\n", ":2: vertex needs at least 3 numbers, got 2"},
      {"short_normal.obj", "vn 0 1\n", ":1: normal needs at least 3 numbers, got 2"},
      {"infinite.obj", "v 0 0 0\nv 0 -inf 0\n", ":2: non-finite number '-inf'"},
      {"huge.obj", "v 0 0 1e39\n", ":1: number out of range '1e39'"},
      {"trailing_junk.obj", "v 0 0 1.5.2\n", ":1: bad number '1.5.2'"},
      {"negative_range.obj", vertices + "f -4 1 2\n", ":4: vertex index -4 out of range (3 defined so far)"},
      {"forward_reference.obj", "f 1 2 3\n" + vertices, ":1: vertex index 1 out of range (0 defined so far)"},
      {"bad_index.obj", vertices + "f 1 2 3x\n", ":4: bad vertex index '3x'"},
      {"comment_in_face.obj", vertices + "f 1 2 3 # no\n", ":4: bad vertex index '#'"},
      {"normal_range.obj", vertices + "vn 0 0 1\nf 1//1 2//2 3//1\n", ":5: normal index 2 out of range"},
      {"texcoord_range.obj", vertices + "f 1/1 2/1 3/1\n", ":4: texture coordinate index 1 out of range"},
      {"empty_normal.obj", vertices + "f 1// 2// 3//\n", ":4: bad normal index ''"},
      {"four_slashes.obj", vertices + "f 1/1/1/1 2 3\n", ":4: bad face vertex '1/1/1/1'"},
      {"lone_f.obj", vertices + "f\n", ":4: face needs at least 3 vertices, got 0"},
      {"tag.obj", vertices + "t crease 100/0/0 1 2\nf 1 2 3\n", ":4: tag declares more values than it has"},
      {"nul.obj", vertices + std::string("f 1 2 3\0", 8) + "\n", ":4: NUL byte"},
      {"vw_joint.obj", vertices + "vw 0 1e30 0.5\nf 1 2 3\n", ":4: bad vw joint '1e30'"},
      {"vw_pairs.obj", vertices + "vw 0 1\nf 1 2 3\n", ":4: vw needs a vertex and joint/weight pairs"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path path = dir.write(c.name, c.contents);
    expectContains(objError(path), path.string() + c.expected);
  }
}

TEST(ObjLoaderErrors, FaceWithTooManyVertices) {
  const TempDir dir;
  std::string contents = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int i = 0; i < 256; ++i) {
    contents += ' ';
    contents += std::to_string(i % 3 + 1);
  }
  const fs::path path = dir.write("big_face.obj", contents + "\n");
  expectContains(objError(path), path.string() + ":4: face has 256 vertices; at most 255 are supported");
}

TEST(ObjLoaderErrors, NeverCrashesOnGarbage) {
  const TempDir dir;
  // Pseudo-random bytes, NULs included.
  std::string junk(1 << 16, '\0');
  uint32_t state = 12345;
  for (char& c : junk) c = static_cast<char>((state = state * 1664525u + 1013904223u) >> 24);
  errorOf([&] { loadObj(dir.write("junk.obj", junk)); });
  // The same without NULs or line ends: lines tinyobjloader would ignore.
  for (char& c : junk)
    if (c == '\0' || c == '\n' || c == '\r') c = 'x';
  EXPECT_NE(objError(dir.write("junk2.obj", junk)).find(": no triangles"), std::string::npos);
  // One endless line is refused without reading it all into memory.
  const fs::path longLine = dir.write("long.obj", "v 0 0 0\n# " + std::string(3 << 20, 'x'));
  expectContains(objError(longLine), longLine.string() + ":2: line longer than 1 MiB");
  // Not regular files: must neither hang (a FIFO, /dev/zero) nor be read.
  expectContains(objError(dir.path()), ": cannot open: not a regular file");
  expectContains(objError("/dev/zero"), "/dev/zero: cannot open: not a regular file");
  const fs::path fifo = dir.path() / "fifo.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectContains(objError(fifo), ": cannot open: not a regular file");
}

TEST(ObjLoaderErrors, RefusesFilesOver2GiB) {
  const TempDir dir;
  const fs::path path = dir.path() / "huge.obj";
  std::ofstream(path).close();
  std::error_code error;
  fs::resize_file(path, (std::uintmax_t{2} << 30) + 1, error);  // sparse: costs no disk
  if (error) GTEST_SKIP() << "cannot make a sparse file here: " << error.message();
  expectContains(objError(path), path.string() + ": file too large (2147483649 bytes; the limit is 2 GiB)");
}

TEST(SceneError, FormatsOneLine) {
  EXPECT_STREQ(SceneError("a.obj", 7, "bad\nthing\n").what(), "a.obj:7: bad thing");
  EXPECT_STREQ(SceneError("a.obj", "no triangles").what(), "a.obj: no triangles");
}

// The same folding for the image libraries' messages (render/exr_io.cpp, oiio_module.cpp).
TEST(OneLineMessage, FoldsLineBreaksAndNamesAnEmptyOne) {
  EXPECT_EQ(oneLineMessage("cannot\r\nwrite\n\n"), "cannot  write");
  EXPECT_EQ(oneLineMessage("\n", "unknown error"), "unknown error");
  EXPECT_EQ(oneLineMessage("fine", "unknown error"), "fine");
}

// --- the Cornell box ------------------------------------------------------------

TEST(CornellBox, HasThe32TrianglesOfFigure26) {
  const Scene scene = makeCornellBox();
  EXPECT_EQ(scene.name, "cornell");
  ASSERT_EQ(scene.triangles.size(), 32u);
  ASSERT_EQ(scene.materialIds.size(), 32u);
  EXPECT_FALSE(scene.hasVertexNormals());
  ASSERT_EQ(scene.materials.size(), 4u);
  for (const Material& m : scene.materials) EXPECT_FALSE(m.isMirror());
  for (uint32_t id : scene.materialIds) EXPECT_LT(id, scene.materials.size());
  expectVec3(scene.materials[scene.materialIds[0]].diffuse, glm::vec3(0.75f));
}

TEST(CornellBox, BoundsAndView) {
  const Scene scene = makeCornellBox();
  const Aabb box = scene.bounds();
  expectVec3(box.min, {0, 0, 0});
  expectVec3(box.max, {556, 548.8f, 559.2f});
  expectVec3(scene.camera.eye, {278, 273, -800});
  expectVec3(scene.camera.lookAt, {278, 273, 0});
  expectVec3(scene.camera.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera.fovDegrees, 39.3f);
  expectVec3(scene.background, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(scene.ambient, 0.1f);
}

TEST(CornellBox, RedWallAtHighXGreenAtZero) {
  const Scene scene = makeCornellBox();
  int red = 0, green = 0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const glm::vec3 colour = scene.materials[scene.materialIds[i]].diffuse;
    if (colour.r > 0.5f && colour.g < 0.1f) {
      ++red;
      EXPECT_GT(scene.triangles[i].centroid().x, 549.0f);
    } else if (colour.g > 0.4f && colour.r < 0.2f) {
      ++green;
      EXPECT_EQ(scene.triangles[i].centroid().x, 0.0f);
    }
  }
  EXPECT_EQ(red, 2);
  EXPECT_EQ(green, 2);
}

TEST(CornellBox, LightHangsBelowTheCeiling) {
  const Scene scene = makeCornellBox();
  const float ceiling = 548.8f;
  // The light square is the last quad: white 0.78, facing down.
  for (std::size_t i = 30; i < 32; ++i) {
    const Triangle& t = scene.triangles[i];
    expectVec3(scene.materials[scene.materialIds[i]].diffuse, glm::vec3(0.78f));
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) {
      EXPECT_LT(p.y, ceiling);
      EXPECT_GT(p.y, ceiling - 2.0f);
      EXPECT_GT(p.y, scene.light.position.y);
    }
    EXPECT_LT(t.geometricNormal().y, 0.0f);
  }
  const glm::vec3 light = scene.light.position;
  EXPECT_GT(light.x, 213.0f);
  EXPECT_LT(light.x, 343.0f);
  EXPECT_GT(light.z, 227.0f);
  EXPECT_LT(light.z, 332.0f);
  expectVec3(scene.light.color, glm::vec3(1.0f));
}

// Walls face into the room and block faces away from their block, so a
// renderer that culls or orients by winding sees what the thesis shows.
TEST(CornellBox, NormalsFaceTheRoom) {
  const Scene scene = makeCornellBox();
  const glm::vec3 room = scene.bounds().center();
  for (std::size_t i = 0; i < 10; ++i)
    EXPECT_GT(glm::dot(scene.triangles[i].geometricNormal(), room - scene.triangles[i].centroid()), 0.0f) << i;
  for (std::size_t block = 0; block < 2; ++block) {
    Aabb box;
    for (std::size_t i = 10 + 10 * block; i < 20 + 10 * block; ++i) box.extend(scene.triangles[i].bounds());
    for (std::size_t i = 10 + 10 * block; i < 20 + 10 * block; ++i) {
      EXPECT_GT(glm::dot(scene.triangles[i].geometricNormal(), scene.triangles[i].centroid() - box.center()), 0.0f)
          << i;
      EXPECT_GT(glm::length(scene.triangles[i].geometricNormal()), 0.0f) << i;
    }
  }
}

// --- the registry ---------------------------------------------------------------

TEST(SceneRegistry, BuiltinNames) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"cows", "robots", "kitchen", "bunny", "cornell"}));
}

TEST(SceneRegistry, LoadsCornell) {
  const Scene scene = loadScene("cornell");
  EXPECT_EQ(scene.name, "cornell");
  EXPECT_EQ(scene.triangles.size(), 32u);
}

TEST(SceneRegistry, UnknownName) {
  EXPECT_EQ(errorOf([] { loadScene("foo"); }),
            "unknown scene 'foo' (expected cows, robots, kitchen, bunny, cornell, spheres, 0-4, conference, sibenik, "
            "sponza, teapot, dragon or a file path)");
}

TEST(SceneRegistry, UnsupportedFormat) {
  const TempDir dir;
  const fs::path path = dir.write("scene.xyz", "whatever");
  EXPECT_EQ(errorOf([&] { loadScene(path.string()); }), path.string() + ": unsupported scene format '.xyz'");
}

TEST(SceneRegistry, MissingObjPathSaysCannotOpen) {
  const fs::path path = kObjData / "nothing_here.obj";
  expectContains(errorOf([&] { loadScene(path.string()); }), path.string() + ": cannot open: ");
}

TEST(SceneRegistry, FramesFileScenes) {
  const fs::path path = kObjData / "quad_pentagon.obj";
  const Scene scene = loadScene(path.string());
  EXPECT_EQ(scene.name, "quad_pentagon");
  EXPECT_EQ(scene.triangles.size(), 5u);
  const Aabb box = scene.bounds();
  expectVec3(scene.camera.lookAt, box.center());
  expectVec3(scene.camera.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera.fovDegrees, 45.0f);
  // In front (+z), looking back at the mesh from beyond its bounding sphere.
  const float r = 0.5f * glm::length(box.extent());
  EXPECT_GT(glm::length(scene.camera.eye - box.center()), 2.0f * r);
  EXPECT_GT(scene.camera.eye.z, box.max.z);
  EXPECT_GT(scene.light.position.y, box.max.y);
  EXPECT_GT(scene.light.position.x, box.max.x);
  EXPECT_GT(scene.light.position.z, box.max.z);
  expectVec3(scene.background, {0.1f, 0.12f, 0.16f});
}

TEST(SceneRegistry, LoadsTheBunny) {
  if (!fs::exists(kBunny)) GTEST_SKIP() << kBunny << " is missing: install the Debian package glmark2-data";
  const Scene scene = loadScene("bunny");
  EXPECT_EQ(scene.name, "bunny");
  EXPECT_EQ(scene.triangles.size(), 69666u);
  EXPECT_EQ(scene.materialIds.size(), 69666u);
  const Aabb box = scene.bounds();
  EXPECT_NEAR(box.min.x, -1.0f, 0.01f);
  EXPECT_NEAR(box.max.x, 1.0f, 0.01f);
  EXPECT_NEAR(box.center().y, 0.0f, 0.02f);
  expectVec3(scene.camera.lookAt, box.center());
}

}  // namespace
}  // namespace passtrace
