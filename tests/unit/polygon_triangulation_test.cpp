// Polygon triangulation (scenes/polygon_triangulation.h) against brute force:
// every polygon is drawn in 2D, placed in a tilted plane, triangulated, and
// the triangles (mapped back to the 2D drawing by index) must cover every
// sample point inside the polygon exactly once and none outside, with the
// shoelace area. Convex polygons must give exactly the fan; non-planar and
// self-intersecting ones the documented flag; garbage must end.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/aff_loader.h"
#include "scenes/obj_loader.h"
#include "scenes/polygon_triangulation.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using P2 = glm::dvec2;

// A plane that is not axis-aligned: 3D point = origin + x * u + y * v.
struct Plane {
  glm::dvec3 origin{0.3, -1.2, 2.5};
  glm::dvec3 u = glm::normalize(glm::dvec3(1.0, 0.4, -0.3));
  glm::dvec3 v = glm::normalize(glm::cross(glm::dvec3(0.2, 0.5, 1.0), u));
  glm::vec3 at(P2 p) const { return glm::vec3(origin + p.x * u + p.y * v); }
};

std::vector<glm::vec3> inPlane(const std::vector<P2>& points, const Plane& plane = {}) {
  std::vector<glm::vec3> out;
  for (const P2& p : points) out.push_back(plane.at(p));
  return out;
}

double cross(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }

double shoelace(const std::vector<P2>& p) {
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) twice += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * twice;
}

// Crossing number (the polygons here are simple).
bool insidePolygon(const std::vector<P2>& p, P2 x) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > x.y) != (p[j].y > x.y) && x.x < p[j].x + (x.y - p[j].y) * (p[i].x - p[j].x) / (p[i].y - p[j].y))
      inside = !inside;
  return inside;
}

bool insideTriangle(P2 a, P2 b, P2 c, P2 x) {
  const double s0 = cross(b - a, x - a), s1 = cross(c - b, x - b), s2 = cross(a - c, x - c);
  return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

std::vector<P2> reversed(std::vector<P2> p) {
  std::reverse(p.begin(), p.end());
  return p;
}

std::vector<P2> rotated(std::vector<P2> p, std::size_t k) {
  std::rotate(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(k), p.end());
  return p;
}

// An L, starting at a convex corner from which the fan leaves the shape.
const std::vector<P2> kL = {{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}};

std::vector<P2> star(int points, double outer, double inner) {
  std::vector<P2> out;
  for (int i = 0; i < 2 * points; ++i) {
    const double angle = std::numbers::pi * i / points + 0.1;
    const double r = i % 2 == 0 ? outer : inner;
    out.push_back({r * std::cos(angle), r * std::sin(angle)});
  }
  return out;
}

// A comb: teeth up from a bar, many reflex corners.
std::vector<P2> comb(int teeth) {
  std::vector<P2> out = {{0, 0}, {2.0 * teeth, 0}};
  for (int i = teeth - 1; i >= 0; --i) {
    out.push_back({2.0 * i + 1.6, 1});
    out.push_back({2.0 * i + 1.6, 3});
    out.push_back({2.0 * i + 0.4, 3});
    out.push_back({2.0 * i + 0.4, 1});
  }
  out.push_back({0, 1});
  return out;
}

// The triangles of a simple polygon drawn as `p`: n - 2 of them, oriented
// as the polygon, with its area, covering every sample inside once and
// none outside.
void expectTriangulates(const std::vector<P2>& p, const PolygonTriangles& got) {
  ASSERT_EQ(got.triangles.size(), p.size() - 2);
  const double orientation = shoelace(p) > 0 ? 1.0 : -1.0;
  double area = 0.0;
  for (const auto& [a, b, c] : got.triangles) {
    ASSERT_LT(std::max({a, b, c}), p.size());
    const double signedArea = 0.5 * cross(p[b] - p[a], p[c] - p[a]);
    EXPECT_GE(orientation * signedArea, -1e-9) << "a triangle turned over: " << a << " " << b << " " << c;
    area += std::fabs(signedArea);
    if (std::fabs(signedArea) > 1e-9) {
      const P2 centroid = (p[a] + p[b] + p[c]) / 3.0;
      EXPECT_TRUE(insidePolygon(p, centroid)) << "triangle " << a << " " << b << " " << c << " lies outside";
    }
  }
  EXPECT_NEAR(area, std::fabs(shoelace(p)), 1e-9 * (1.0 + area));
  P2 lo = p[0], hi = p[0];
  for (const P2& x : p) {
    lo = glm::min(lo, x);
    hi = glm::max(hi, x);
  }
  constexpr int kSamples = 157;  // odd offsets keep samples off edges and diagonals
  int wrong = 0;
  for (int i = 0; i < kSamples; ++i)
    for (int j = 0; j < kSamples; ++j) {
      const P2 x = lo + (hi - lo) * P2((i + 0.4137) / kSamples, (j + 0.5871) / kSamples);
      int covered = 0;
      for (const auto& [a, b, c] : got.triangles) covered += insideTriangle(p[a], p[b], p[c], x);
      wrong += covered != (insidePolygon(p, x) ? 1 : 0);
    }
  EXPECT_EQ(wrong, 0) << "samples covered other than once inside, never outside";
}

void expectFan(const PolygonTriangles& got, std::size_t n) {
  ASSERT_EQ(got.triangles.size(), n - 2);
  for (std::size_t i = 0; i + 2 < n; ++i) {
    EXPECT_EQ(got.triangles[i][0], 0u);
    EXPECT_EQ(got.triangles[i][1], i + 1);
    EXPECT_EQ(got.triangles[i][2], i + 2);
  }
}

// Indices in range, n - 2 triangles, each of three distinct corners.
void expectWellFormed(const PolygonTriangles& got, std::size_t n) {
  ASSERT_EQ(got.triangles.size(), n < 3 ? 0 : n - 2);
  for (const auto& [a, b, c] : got.triangles) {
    EXPECT_LT(std::max({a, b, c}), n);
    EXPECT_TRUE(a != b && b != c && a != c);
  }
}

TEST(PolygonTriangulation, ConvexPolygonsGiveExactlyTheFan) {
  std::vector<std::vector<P2>> convex = {
      {{0, 0}, {1, 0}, {1, 1}, {0, 1}},
      {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}},            // a collinear vertex
      {{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}},    // duplicates, closing one too
      {{0, 0}, {1e-3, 0}, {1e-3, 1e-3}, {0, 1e-3}},        // small
      {{0, 0}, {3e30, 0}, {3e30, 2e30}, {0, 2e30}},        // large
  };
  // A regular k-gon with its edges' midpoints.
  for (int k = 3; k <= 40; k += 7) convex.push_back(star(k, 1.0, std::cos(std::numbers::pi / k)));
  for (const auto& p : convex)
    for (const auto& q : {p, reversed(p)}) {
      const PolygonTriangles got = triangulatePolygon(inPlane(q));
      EXPECT_EQ(got.shape, PolygonShape::Convex) << q.size();
      expectFan(got, q.size());
    }
  // A triangle, even one without area, is itself.
  const PolygonTriangles three = triangulatePolygon({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});
  EXPECT_EQ(three.shape, PolygonShape::Convex);
  expectFan(three, 3);
  EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}).triangles.empty());
}

TEST(PolygonTriangulation, AnLShapeFromEveryStartBothWindings) {
  for (std::size_t k = 0; k < kL.size(); ++k)
    for (const auto& p : {rotated(kL, k), reversed(rotated(kL, k))}) {
      SCOPED_TRACE("start " + std::to_string(k));
      const PolygonTriangles got = triangulatePolygon(inPlane(p));
      EXPECT_EQ(got.shape, PolygonShape::Concave);
      expectTriangulates(p, got);
    }
}

TEST(PolygonTriangulation, StarsAndCombs) {
  for (int points : {3, 5, 7, 12}) {
    const std::vector<P2> s = star(points, 1.0, 0.4);
    for (std::size_t k = 0; k < 3; ++k) {
      SCOPED_TRACE(std::to_string(points) + " points, start " + std::to_string(k));
      const PolygonTriangles got = triangulatePolygon(inPlane(rotated(s, k)));
      EXPECT_EQ(got.shape, PolygonShape::Concave);
      expectTriangulates(rotated(s, k), got);
    }
  }
  for (int teeth : {1, 4, 30}) {
    SCOPED_TRACE(std::to_string(teeth) + " teeth");
    const PolygonTriangles got = triangulatePolygon(inPlane(comb(teeth)));
    EXPECT_EQ(got.shape, PolygonShape::Concave);
    expectTriangulates(comb(teeth), got);
  }
}

TEST(PolygonTriangulation, CollinearAndDuplicateVertices) {
  // The L with vertices along its edges, a repeated corner, a repeated
  // closing vertex and a repeated reflex corner.
  const std::vector<std::vector<P2>> cases = {
      {{2, 0}, {2, 0.5}, {2, 1}, {1.5, 1}, {1, 1}, {1, 1.5}, {1, 2}, {0.5, 2}, {0, 2}, {0, 1}, {0, 0}, {1, 0}},
      {{2, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}},
      {{2, 0}, {2, 1}, {1, 1}, {1, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}},
      // Every edge split in three, with one split point doubled.
      {{2, 0}, {2, 1.0 / 3}, {2, 2.0 / 3}, {2, 1}, {5.0 / 3, 1}, {4.0 / 3, 1}, {4.0 / 3, 1}, {1, 1}, {1, 2}, {0, 2},
       {0, 0}},
  };
  for (const auto& p : cases)
    for (const auto& q : {p, reversed(p)}) {
      SCOPED_TRACE(std::to_string(q.size()) + " vertices");
      const PolygonTriangles got = triangulatePolygon(inPlane(q));
      EXPECT_EQ(got.shape, PolygonShape::Concave);
      expectTriangulates(q, got);
    }
}

TEST(PolygonTriangulation, RandomSimplePolygonsAgainstBruteForce) {
  // Star-shaped about the origin (increasing angles, less than pi apart so
  // the origin stays inside; random radii): simple, and concave more often
  // than not.
  std::mt19937 random(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int concave = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 4 + trial % 40;
    std::vector<P2> p;
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * std::numbers::pi * (i + 0.8 * unit(random)) / n;
      p.push_back((0.2 + unit(random)) * P2(std::cos(a), std::sin(a)));
    }
    if (trial % 2 == 1) p = reversed(p);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const PolygonTriangles got = triangulatePolygon(inPlane(p));
    ASSERT_NE(got.shape, PolygonShape::Irregular);
    concave += got.shape == PolygonShape::Concave;
    expectTriangulates(p, got);
    if (got.shape == PolygonShape::Convex) expectFan(got, p.size());
  }
  EXPECT_GT(concave, 150);
}

TEST(PolygonTriangulation, NonPlanarPolygonsAreFlaggedAndClippedInProjection) {
  // A star with one tip lifted off its plane by 5% of its size (a star: an
  // L has diagonals through its reflex corner, which a tilt could open).
  const Plane plane;
  const std::vector<P2> s = star(5, 1.0, 0.4);
  std::vector<glm::vec3> lifted = inPlane(s, plane);
  lifted[4] += glm::vec3(0.1 * glm::cross(plane.u, plane.v));
  const PolygonTriangles got = triangulatePolygon(lifted);
  EXPECT_EQ(got.shape, PolygonShape::Irregular);
  expectTriangulates(s, got);  // the projection is nearly the star itself
  // A warped quad: convex in projection, so still the fan, but flagged.
  const PolygonTriangles quad = triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3f}, {0, 1, 0}});
  EXPECT_EQ(quad.shape, PolygonShape::Irregular);
  expectFan(quad, 4);
  // Float noise is not non-planarity.
  std::vector<glm::vec3> noisy = inPlane(kL, plane);
  noisy[2] += glm::vec3(1e-7f, -1e-7f, 1e-7f);
  EXPECT_EQ(triangulatePolygon(noisy).shape, PolygonShape::Concave);
}

TEST(PolygonTriangulation, SelfIntersectingPolygonsAreFlagged) {
  const std::vector<std::vector<P2>> cases = {
      {{0, 0}, {2, 2}, {2, 0}, {0, 2}},             // a symmetric bow-tie: no net area
      {{0, 0}, {3, 2}, {3, 0}, {0, 1}},             // a lopsided one
      {{0, 0}, {2, 0}, {2, 1}, {3, 1}, {3, -1}, {1, -1}, {1, 2}, {0, 2}},  // a figure with a loop
  };
  for (const auto& p : cases) {
    const PolygonTriangles got = triangulatePolygon(inPlane(p));
    EXPECT_EQ(got.shape, PolygonShape::Irregular) << p.size();
    expectWellFormed(got, p.size());
  }
  // A pentagram turns left at every corner but winds twice.
  std::vector<P2> pentagram;
  for (int i = 0; i < 5; ++i) {
    const double a = 4.0 * std::numbers::pi * i / 5;
    pentagram.push_back({std::cos(a), std::sin(a)});
  }
  const PolygonTriangles got = triangulatePolygon(inPlane(pentagram));
  EXPECT_EQ(got.shape, PolygonShape::Irregular);
  expectWellFormed(got, 5);
}

TEST(PolygonTriangulation, PolygonsWithoutAreaAreFanned) {
  const PolygonTriangles line = triangulatePolygon({{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}, {1, 1, 1}});
  EXPECT_EQ(line.shape, PolygonShape::Convex);
  expectFan(line, 5);
  const PolygonTriangles point = triangulatePolygon(std::vector<glm::vec3>(6, glm::vec3(4, 5, 6)));
  EXPECT_EQ(point.shape, PolygonShape::Convex);
  expectFan(point, 6);
}

TEST(PolygonTriangulation, HugeConcavePolygonsAreFannedAndFlagged) {
  const std::vector<P2> s = star(static_cast<int>(kMaxEarClippingVertices) / 2 + 1, 1.0, 0.5);
  const PolygonTriangles got = triangulatePolygon(inPlane(s));
  EXPECT_EQ(got.shape, PolygonShape::TooLarge);
  expectFan(got, s.size());
}

TEST(PolygonTriangulation, GarbageEndsWellFormed) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick(0, 5);
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t n = 3 + static_cast<std::size_t>(trial % 60);
    std::vector<glm::vec3> p;
    for (std::size_t i = 0; i < n; ++i) {
      // Some planar, some repeating earlier vertices, some scattered.
      glm::vec3 v(coordinate(random), coordinate(random), trial % 3 == 0 ? 0.0f : coordinate(random));
      if (pick(random) == 0 && !p.empty()) v = p[static_cast<std::size_t>(random() % p.size())];
      p.push_back(v);
    }
    expectWellFormed(triangulatePolygon(p), n);
  }
}

TEST(PolygonWarnings, OneLinePerKindCounted) {
  PolygonWarnings warnings;
  EXPECT_EQ(warnings.text("a.obj"), "");
  for (PolygonShape s : {PolygonShape::Convex, PolygonShape::Concave, PolygonShape::Irregular}) warnings.count(s);
  EXPECT_EQ(warnings.text("a.obj"),
            "a.obj: 1 polygon was non-planar or self-intersecting: triangulated by ear clipping of the projection onto "
            "the Newell plane (a fan where clipping cannot finish)\n");
  warnings.count(PolygonShape::Irregular);
  warnings.count(PolygonShape::TooLarge);
  const std::string text = warnings.text("a.obj");
  EXPECT_EQ(text.rfind("a.obj: 2 polygons were non-planar or self-intersecting", 0), 0u) << text;
  EXPECT_NE(text.find("\na.obj: 1 polygon was concave with more than 4096 vertices"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

// --- in the loaders: normals follow their vertices, one warning per file ---

class PolygonFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("passtrace-polygons-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

// The L's vertices as "x y 0" lines, each with the normal (x, y, 1)
// normalized where `withNormals`, so a normal tells its vertex.
std::string lVertices(const char* prefix, bool withNormals) {
  std::string out;
  for (const P2& p : kL) {
    out += prefix + std::to_string(p.x) + " " + std::to_string(p.y) + " 0";
    if (withNormals) out += "  " + std::to_string(p.x) + " " + std::to_string(p.y) + " 1";
    out += "\n";
  }
  return out;
}

void expectLWithNormals(const Scene& scene) {
  ASSERT_EQ(scene.triangles.size(), 4u);
  ASSERT_EQ(scene.vertexNormals.size(), 4u);
  PolygonTriangles asIndices;
  const auto indexOf = [](const glm::vec3& v) {
    for (std::size_t i = 0; i < kL.size(); ++i)
      if (glm::length(glm::dvec3(v) - glm::dvec3(kL[i], 0.0)) < 1e-6) return static_cast<uint32_t>(i);
    ADD_FAILURE() << "not a vertex of the L";
    return uint32_t{0};
  };
  for (std::size_t t = 0; t < 4; ++t) {
    const Triangle& tri = scene.triangles[t];
    const std::array<glm::vec3, 3> corners = {tri.v0, tri.v1, tri.v2};
    std::array<uint32_t, 3> ids{};
    for (int k = 0; k < 3; ++k) {
      ids[k] = indexOf(corners[k]);
      const glm::vec3 expected = glm::normalize(glm::vec3(corners[k].x, corners[k].y, 1.0f));
      // OBJ keeps its normals' lengths, AFF normalizes them.
      EXPECT_LT(glm::length(glm::normalize(scene.vertexNormals[t][k]) - expected), 1e-5f)
          << "triangle " << t << " corner " << k;
    }
    asIndices.triangles.push_back(ids);
  }
  expectTriangulates(kL, asIndices);
}

TEST_F(PolygonFiles, ObjFacesAreClippedWithNormalsFollowingTheirVertices) {
  std::string obj = lVertices("v ", false);
  for (const P2& p : kL) obj += "vn " + std::to_string(p.x) + " " + std::to_string(p.y) + " 1\n";
  obj += "f 1//1 2//2 3//3 4//4 5//5 6//6\n";
  ::testing::internal::CaptureStderr();
  const Scene scene = loadObj(write("l.obj", obj));
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  expectLWithNormals(scene);
}

TEST_F(PolygonFiles, AffPatchesAreClippedWithNormalsFollowingTheirVertices) {
  ::testing::internal::CaptureStderr();
  const Scene scene = loadAff(write("l.aff", "pp 6\n" + lVertices("", true)));
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  expectLWithNormals(scene);
}

TEST_F(PolygonFiles, EachLoaderWarnsOncePerFileCountingIrregularPolygons) {
  const std::string bowTie = "0 0 0\n2 2 0\n2 0 0\n0 2 0\n";
  const std::string warped = "0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n";
  ::testing::internal::CaptureStderr();
  const fs::path nff = write("bad.nff", "p 4\n" + bowTie + "p 4\n" + warped + "p 6\n" + lVertices("", false));
  const Scene fromNff = loadAff(nff);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            nff.string() + ": 2 polygons were non-planar or self-intersecting: triangulated by ear clipping of the "
                           "projection onto the Newell plane (a fan where clipping cannot finish)\n");
  EXPECT_EQ(fromNff.triangles.size(), 2u + 2u + 4u);

  ::testing::internal::CaptureStderr();
  const fs::path obj = write("bad.obj", "v 0 0 0\nv 2 2 0\nv 2 0 0\nv 0 2 0\nf 1 2 3 4\nf 4 3 2 1\nf 1 3 2\n");
  const Scene fromObj = loadObj(obj);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.rfind(obj.string() + ": 2 polygons were non-planar or self-intersecting", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(fromObj.triangles.size(), 5u);
}

}  // namespace
}  // namespace passtrace
