// passtrace's own PLY body reader (scenes/ply_reader.h) on files written by
// tests/ply_writer.h: every format, scalar type and list-count type, extra
// properties and elements, binary bodies whose first byte Assimp 5.2 skipped
// (issue #5341), and the errors a corrupt body gives.

#include <bit>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "scenes/ply_reader.h"
#include "scenes/scene_error.h"
#include "tests/ply_writer.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::PlyLayout;
using test::PlyMesh;

// A square (a quad: two triangles) under an apex, and one triangle on it:
// integer coordinates, so that every scalar type holds them.
PlyMesh squareAndApex() {
  return {{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 2}}, {{0, 1, 2, 3}, {0, 1, 4}, {1, 2, 4}}};
}

// The triangles the reader must give for m: its faces in order, a quad as
// the fan (0 1 2), (0 2 3).
std::vector<Triangle> expectedTriangles(const PlyMesh& m) {
  std::vector<Triangle> out;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      out.push_back({m.vertices[static_cast<std::size_t>(f[0])], m.vertices[static_cast<std::size_t>(f[i])],
                     m.vertices[static_cast<std::size_t>(f[i + 1])]});
  return out;
}

class PlyReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("passtrace_ply_reader_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  // The message of the SceneError loading `bytes` throws.
  std::string errorOf(const std::string& bytes) {
    const fs::path p = write("bad.ply", bytes);
    try {
      loadPly(p);
    } catch (const SceneError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.find('\n'), std::string::npos);
      EXPECT_EQ(m.rfind(p.string(), 0), 0u) << m;
      return m.substr(p.string().size());
    }
    ADD_FAILURE() << "loaded";
    return {};
  }

  fs::path dir_;
};

void expectTriangles(const Scene& s, const std::vector<Triangle>& want) {
  ASSERT_EQ(s.triangles.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(s.triangles[i].v0, want[i].v0) << "triangle " << i;
    EXPECT_EQ(s.triangles[i].v1, want[i].v1) << "triangle " << i;
    EXPECT_EQ(s.triangles[i].v2, want[i].v2) << "triangle " << i;
  }
}

// Rays down onto the mesh and across it: every hit of the loaded scene is
// brute force's hit on the triangles written.
void expectSameHits(const Scene& s, const std::vector<Triangle>& want) {
  int found = 0;
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 21; ++j) {
      const glm::vec3 target(-0.5f + 0.15f * static_cast<float>(i), -0.5f + 0.15f * static_cast<float>(j), 0.5f);
      for (const Ray& ray : {Ray{glm::vec3(target.x, target.y, 5.0f), {0, 0, -1}},
                             Ray{glm::vec3(-5.0f, target.y, target.x * 0.5f), {1, 0, 0}}}) {
        const Hit a = intersectBruteForce(s.triangles, ray, false);
        const Hit b = intersectBruteForce(want, ray, false);
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.t, b.t);
        found += a.found();
      }
    }
  EXPECT_GT(found, 100);
}

// Assimp 5.2 skipped a whitespace byte after end_header, misreading a
// binary body that starts with one (issue #5341).
TEST_F(PlyReaderTest, BinaryBodiesStartingWithWhitespaceBytes) {
  for (const char* format : {"binary_little_endian", "binary_big_endian"})
    for (const uint32_t first : {0x0Au, 0x0Du, 0x20u, 0x09u}) {
      SCOPED_TRACE(std::string(format) + " first byte " + std::to_string(first));
      PlyMesh m = squareAndApex();
      const bool big = std::string(format) == "binary_big_endian";
      // The first x's first byte in the file: its low byte (about -0.5) or
      // its high byte (a tiny positive number) by byte order.
      m.vertices[0].x = std::bit_cast<float>(big ? first << 24 : 0xBF000000u | first);
      const std::string bytes = test::plyFile(m, {.format = format});
      const std::size_t body = bytes.find("end_header\n") + 11;
      ASSERT_EQ(static_cast<unsigned char>(bytes[body]), first);
      const Scene s = loadPly(write("scan.ply", bytes));
      expectTriangles(s, expectedTriangles(m));
      expectSameHits(s, expectedTriangles(m));
    }
}

TEST_F(PlyReaderTest, EveryFormatAndTypeGivesTheSameTriangles) {
  const PlyMesh m = squareAndApex();
  const std::vector<Triangle> want = expectedTriangles(m);
  const char* const kIntegers[] = {"char", "uchar", "short", "ushort", "int", "uint",
                                   "int8", "uint8", "int16", "uint16", "int32", "uint32"};
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    SCOPED_TRACE(format);
    const auto check = [&](const PlyLayout& layout, const std::string& what) {
      SCOPED_TRACE(what);
      expectTriangles(loadPly(write("t.ply", test::plyFile(m, layout))), want);
    };
    for (const char* type : kIntegers) {
      check({.format = format, .positionType = type}, std::string("positions ") + type);
      check({.format = format, .countType = type}, std::string("count ") + type);
      check({.format = format, .indexType = type}, std::string("indices ") + type);
    }
    for (const char* type : {"float", "float32", "double", "float64"})
      check({.format = format, .positionType = type}, std::string("positions ") + type);
    check({.format = format, .extraLists = true}, "extra scalar and list properties");
    check({.format = format, .stanfordExtras = true}, "confidence, intensity, range_grid");
    check({.format = format, .indexName = "vertex_index"}, "vertex_index");
  }
}

// The Stanford scans' layout (dragon_vrip.ply, bun_zipper.ply): x y z
// confidence intensity as floats, faces as uchar count and int indices.
TEST_F(PlyReaderTest, StanfordScanLayout) {
  PlyMesh m = squareAndApex();
  m.vertices[1].x = 2.75f;
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    SCOPED_TRACE(format);
    const Scene s = loadPly(write("scan.ply", test::plyFile(m, {.format = format, .stanfordExtras = true})));
    expectTriangles(s, expectedTriangles(m));
    EXPECT_EQ(s.name, "scan");
    EXPECT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materialIds, std::vector<uint32_t>(s.triangles.size(), 0));
    EXPECT_TRUE(s.vertexNormals.empty());
  }
}

// An ASCII header: `vertices` of x y z and the given further properties,
// then the given lines (faces or strips).
std::string asciiHeader(int vertices, const std::string& vertexExtras, const std::string& then) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\n" + vertexExtras + then + "end_header\n";
}

TEST_F(PlyReaderTest, NormalsWhenTheFileHasThem) {
  const std::string text = asciiHeader(3, "property float nx\nproperty float ny\nproperty float nz\n",
                                       "element face 1\nproperty list uchar int vertex_indices\n") +
                           "0 0 0 0 0 2\n1 0 0 0 0 0\n0 1 0 0 1 0\n3 0 1 2\n";
  const Scene s = loadPly(write("n.ply", text));
  ASSERT_EQ(s.vertexNormals.size(), 1u);
  EXPECT_EQ(s.vertexNormals[0][0], glm::vec3(0, 0, 1));  // normalised
  EXPECT_EQ(s.vertexNormals[0][1], glm::vec3(0, 0, 1));  // zero: the geometric normal
  EXPECT_EQ(s.vertexNormals[0][2], glm::vec3(0, 1, 0));
}

TEST_F(PlyReaderTest, TriangleStrips) {
  const std::string text = asciiHeader(5, "", "element tristrips 1\nproperty list int int vertex_indices\n") +
                           "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 0\n8 0 1 2 3 -1 1 3 4\n";
  const Scene s = loadPly(write("strip.ply", text));
  const glm::vec3 v[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 2, 0}};
  expectTriangles(s, {{v[0], v[1], v[2]}, {v[2], v[1], v[3]}, {v[1], v[3], v[4]}});
}

TEST_F(PlyReaderTest, BlankLinesAndCrlfInAsciiBodies) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n0 0 0\r\n\r\n1 0 0\r\n0 1 0\r\n"
      "3 0 1 2\r\n\r\n";
  EXPECT_EQ(loadPly(write("crlf.ply", text)).triangles.size(), 1u);
}

const std::string kTriangleHeader = asciiHeader(3, "", "element face 1\nproperty list uchar int vertex_indices\n");

TEST_F(PlyReaderTest, OutOfRangeIndexIsAnErrorNamingTheFace) {
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), ":13: face 0 names vertex 7 of 3");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), ":13: face 0 names vertex -1 of 3");
  PlyMesh m = squareAndApex();
  m.faces[1][2] = 5;
  for (const char* format : {"binary_little_endian", "binary_big_endian"})
    EXPECT_EQ(errorOf(test::plyFile(m, {.format = format})), ": face 1 names vertex 5 of 5");
}

TEST_F(PlyReaderTest, CorruptBodiesAreOneLineErrors) {
  const std::string good = test::plyFile(squareAndApex(), {});
  EXPECT_EQ(errorOf(good.substr(0, good.size() - 3)), ": binary body ends inside face 2 of 3 (truncated file?)");
  EXPECT_EQ(errorOf(kTriangleHeader + "0.0000 0 0\n1.0000 0 0\n0.0000 1 0\n"), ":12: face 0: the file ends before this face (truncated file?)");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n"), ":11: vertex 1: 'x' is not a number");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0 4\n0 1 0\n3 0 1 2\n"), ":11: vertex 1: 4 values on the line, 3 expected");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"), ":13: face 0: '1.5' is not a whole number");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"), ":13: face 0: '300' does not fit a uchar");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"), ":14: text after the last element");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), ":11: vertex 1 is not finite");
  EXPECT_EQ(errorOf(kTriangleHeader + "0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n"), ":11: vertex 1 is not finite");
  PlyMesh inf = squareAndApex();
  inf.vertices[3].y = std::numeric_limits<float>::infinity();
  EXPECT_EQ(errorOf(test::plyFile(inf, {})), ": vertex 3 is not finite");
}

// Counts the file cannot hold fail before anything is allocated for them.
TEST_F(PlyReaderTest, HugeCountsInASmallFile) {
  std::string header = test::plyFile(squareAndApex(), {});
  header.replace(header.find("element vertex 5"), 16, "element vertex 2147483648");
  EXPECT_EQ(errorOf(header).rfind(":4: element 'vertex' declares 2147483648 instances", 0), 0u);
  PlyMesh m = squareAndApex();
  std::string list = test::plyFile(m, {.countType = "uint"});
  const std::size_t firstFace = list.size() - (4 + 4 * 4) - 2 * (4 + 3 * 4);
  list[firstFace + 3] = '\x7f';  // a count near 2^31
  EXPECT_EQ(errorOf(list), ": binary body ends inside face 0 of 3 (truncated file?)");
}

TEST_F(PlyReaderTest, FacesWithoutIndexListAreAnError) {
  const std::string text =
      asciiHeader(3, "", "element face 1\nproperty list uchar int corners\n") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(errorOf(text), ":7: element 'face' has no list vertex_indices (or vertex_index)");
}

// The real scans where ../shared/scenes/real exists (a user's machine has
// none): their triangle counts as the folder's README gives them.
TEST_F(PlyReaderTest, RealScansWhenPresent) {
  const fs::path real = (fs::path(PASSTRACE_TEST_DATA) / ".." / ".." / ".." / "shared" / "scenes" / "real").lexically_normal();
  if (!fs::is_directory(real)) GTEST_SKIP() << real << " not found (the real scenes are not shipped with passtrace)";
  const std::pair<const char*, std::size_t> scans[] = {
      {"dragon/dragon_vrip.ply", 871414}, {"conference/conference.ply", 331179}, {"sibenik/sibenik.ply", 75284}};
  for (const auto& [name, triangles] : scans) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(loadPly(real / name).triangles.size(), triangles) << name;
    std::cout << name << ": " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s\n";
  }
}

}  // namespace
}  // namespace passtrace
