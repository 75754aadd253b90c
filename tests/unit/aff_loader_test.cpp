// The NFF/AFF loader, Kochanek–Bartels splines, tessellation, the BART
// scenes (Kitchen and Robots, skipped when ../shared is absent) and the
// registry's AFF dispatch and scene names.

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scenes/aff_loader.h"
#include "scenes/kochanek_bartels.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"
#include "scenes/tessellate.h"
#include "tests/bart_dir.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

const fs::path kAffData = fs::path(PASSTRACE_TEST_DATA) / "aff";

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

std::string affError(const fs::path& path) {
  try {
    loadAff(path);
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for " << path;
  return {};
}

// "FILE:LINE: " followed by a reason containing `part`.
void expectError(const std::string& name, std::size_t line, const std::string& part) {
  const fs::path path = kAffData / name;
  const std::string message = affError(path);
  const std::string prefix = path.string() + ":" + std::to_string(line) + ": ";
  EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
  EXPECT_NE(message.find(part), std::string::npos) << "\"" << message << "\" lacks \"" << part << "\"";
}

using test::bartDir;

// --- NFF primitives --------------------------------------------------------------

TEST(NffLoader, EveryPrimitive) {
  const Scene scene = loadAff(kAffData / "primitives.nff");
  EXPECT_EQ(scene.name, "primitives");
  // quad 2 + patch 1 + sphere 2*16*7 + cylinder 2*16 + cone 16.
  EXPECT_EQ(scene.triangles.size(), 2u + 1u + 224u + 32u + 16u);
  ASSERT_EQ(scene.vertexNormals.size(), scene.triangles.size());
  ASSERT_EQ(scene.materialIds.size(), scene.triangles.size());
  // The polygon is a fan in file order.
  const Triangle& t0 = scene.triangles[0];
  expectNear(t0.v0, {0, 0, 0});
  expectNear(t0.v1, {1, 0, 0});
  expectNear(t0.v2, {1, 1, 0});
  expectNear(scene.triangles[1].v2, {0, 1, 0});
  expectNear(scene.vertexNormals[0][0], {0, 0, 1});
  // Sphere vertices lie on the sphere, normals point out.
  for (std::size_t i = 3; i < 3 + 224; ++i) {
    EXPECT_NEAR(glm::length(scene.triangles[i].v0 - glm::vec3(0, 3, 0)), 0.5f, 1e-5f);
    expectNear(scene.vertexNormals[i][0], glm::normalize(scene.triangles[i].v0 - glm::vec3(0, 3, 0)));
  }
  // Cylinder vertices lie on the radius-1 cylinder around x = 0, z = -2.
  for (std::size_t i = 227; i < 227 + 32; ++i) {
    const glm::vec3 p = scene.triangles[i].v1;
    EXPECT_NEAR(std::hypot(p.x, p.z + 2.0f), 1.0f, 1e-5f);
  }
  // Materials: f's colour times Kd; the Ks 0.97, T 0 one is a mirror.
  const Material& first = scene.materials[scene.materialIds[0]];
  expectNear(first.diffuse, {0.8f, 0.4f, 0.2f});
  EXPECT_FALSE(first.isMirror());
  const Material& shiny = scene.materials[scene.materialIds[3]];
  EXPECT_TRUE(shiny.isMirror());
  expectNear(shiny.mirror, glm::vec3(0.97f));
  // View, background, light rule (first position, summed colour).
  expectNear(scene.camera.eye, {0, 1, 10});
  expectNear(scene.camera.lookAt, {0, 1, 0});
  expectNear(scene.camera.up, {0, 1, 0});
  EXPECT_EQ(scene.camera.fovDegrees, 30.0f);
  expectNear(scene.background, {0.2f, 0.3f, 0.4f});
  expectNear(scene.light.position, {5, 10, 5});
  expectNear(scene.light.color, glm::vec3(1.5f));
  EXPECT_FLOAT_EQ(scene.ambient, 0.1f);  // no am: the default
}

TEST(NffLoader, RegistryDispatchesNff) {
  const Scene scene = loadScene((kAffData / "primitives.nff").string());
  EXPECT_EQ(scene.triangles.size(), 275u);
  expectNear(scene.camera.eye, {0, 1, 10});  // the file's view, not a framed one
}

// --- AFF meshes, transforms, includes, animation -----------------------------------

TEST(AffLoader, MeshWithNormalsTexcoordsAndTransforms) {
  const Scene scene = loadAff(kAffData / "mesh.aff");
  ASSERT_EQ(scene.triangles.size(), 3u);
  // scale 2, rotate 90 degrees about z, translate (10, 0, 0), of (v + (0, 0, 5)).
  expectNear(scene.triangles[0].v0, {10, 0, 10});
  expectNear(scene.triangles[0].v1, {10, 2, 10});
  expectNear(scene.triangles[0].v2, {8, 2, 10});
  expectNear(scene.triangles[1].v2, {8, 0, 10});
  // Normal (0, 0, 1) stays, normal (1, 0, 0) turns to (0, 1, 0).
  expectNear(scene.vertexNormals[0][0], {0, 0, 1});
  expectNear(scene.vertexNormals[0][2], {0, 1, 0});
  // The untransformed mesh without normals gets its geometric normal.
  expectNear(scene.triangles[2].v0, {0, 1, 0});
  expectNear(scene.vertexNormals[2][0], {0, 0, -1});
  // fm: diffuse rgb; Ks 0.2 is no mirror; am 2 -> ambient 0.6, clamped to 0.4.
  const Material& m = scene.materials[scene.materialIds[0]];
  expectNear(m.diffuse, {0.5f, 0.25f, 0.125f});
  EXPECT_FALSE(m.isMirror());
  EXPECT_FLOAT_EQ(scene.ambient, 0.4f);
  // No view or light in the file: both framed on the bounds.
  expectNear(scene.camera.lookAt, scene.bounds().center());
  EXPECT_GT(scene.light.position.y, scene.bounds().max.y);
}

TEST(AffLoader, IncludesAreRelativeToTheIncludingFileAndInstanced) {
  const Scene scene = loadAff(kAffData / "include_main.aff");
  ASSERT_EQ(scene.triangles.size(), 4u);  // (leg + foot) twice
  expectNear(scene.triangles[0].v1, {-1, 1, 0});
  expectNear(scene.triangles[1].v1, {-0.5f, 0, 0});
  expectNear(scene.triangles[2].v1, {1, 1, 0});
  expectNear(scene.triangles[3].v2, {1, 0, 0.5f});
}

TEST(AffLoader, AnimatedTransformsFollowTheKeysAtTheGivenTime) {
  const fs::path file = kAffData / "animated.aff";
  const Scene at0 = loadAff(file);
  ASSERT_EQ(at0.triangles.size(), 2u);
  expectNear(at0.triangles[0].v1, {2, 0, 0});   // scale 2 only
  expectNear(at0.triangles[1].v1, {1, 0, 0});   // no keys: identity
  const Scene at10 = loadAff(file, 10.0f);
  expectNear(at10.triangles[0].v1, {10, 2, 0}); // translate 10, rotate 90
  const Scene at5 = loadAff(file, 5.0f);
  const float h = std::sqrt(2.0f);
  expectNear(at5.triangles[0].v1, {5 + h, h, 0}, 1e-4f);  // halfway
  // `k camera` overrides the v view's placement; the v angle stays.
  expectNear(at0.camera.eye, {1, 2, 3});
  expectNear(at0.camera.lookAt, {0, 2, 3});
  expectNear(at0.camera.up, {0, 1, 0});
  EXPECT_EQ(at0.camera.fovDegrees, 50.0f);
  const Scene after = loadAff(file, 50.0f);               // held after the last key
  expectNear(after.triangles[0].v1, {10, 2, 0});
  // Through the registry's options.
  SceneOptions options;
  options.time = 10.0f;
  expectNear(loadScene(file.string(), options).triangles[0].v1, {10, 2, 0});
}

TEST(AffLoader, StrayNumbersOnACommandsLineAreIgnored) {
  const Scene scene = loadAff(kAffData / "stray.aff");
  EXPECT_EQ(scene.triangles.size(), 1u);
  EXPECT_FALSE(scene.materials[scene.materialIds[0]].isMirror());  // Ks 0.9 < 0.95
}

TEST(AffLoader, MirrorRule) {
  const Scene scene = loadAff(kAffData / "mirrors.aff");
  ASSERT_EQ(scene.triangles.size(), 4u);
  const Material& mirror = scene.materials[scene.materialIds[0]];
  EXPECT_TRUE(mirror.isMirror());
  expectNear(mirror.mirror, {1.0f, 0.97f, 0.96f});
  expectNear(mirror.diffuse, {0.1f, 0.1f, 0.1f});
  EXPECT_FALSE(scene.materials[scene.materialIds[1]].isMirror());  // transmissive
  EXPECT_FALSE(scene.materials[scene.materialIds[2]].isMirror());  // shine 157
  EXPECT_FALSE(scene.materials[scene.materialIds[3]].isMirror());  // one channel 0.9
}

TEST(AffLoader, WhittedTermsOfFm) {
  const Scene scene = loadAff(kAffData / "mirrors.aff");
  const Material& glass = scene.materials[scene.materialIds[1]];  // T 0.5, index 1.5
  EXPECT_FLOAT_EQ(glass.transmission, 0.5f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  expectNear(glass.specular, {1.0f, 1.0f, 1.0f});
  EXPECT_FLOAT_EQ(glass.shininess, 5000.0f);
  const Material& shiny = scene.materials[scene.materialIds[2]];  // T 0, index 1
  EXPECT_EQ(shiny.transmission, 0.0f);
  EXPECT_EQ(shiny.ior, 1.0f);
  EXPECT_FLOAT_EQ(shiny.shininess, 157.0f);
}

TEST(AffLoader, WhittedTermsDefaultsAndClamps) {
  EXPECT_EQ(Material{}.transmission, 0.0f);  // documented defaults: opaque, ior 1.5, no highlight
  EXPECT_EQ(Material{}.ior, 1.5f);
  EXPECT_EQ(Material{}.specular, glm::vec3(0.0f));
  const Scene scene = loadAff(kAffData / "whitted_terms.aff");
  ASSERT_EQ(scene.triangles.size(), 2u);
  const Material& nff = scene.materials[scene.materialIds[0]];  // f: Ks colours the highlight; T 2 clamps to 1
  expectNear(nff.specular, {0.25f, 0.125f, 0.0f});
  EXPECT_EQ(nff.transmission, 1.0f);
  EXPECT_FLOAT_EQ(nff.ior, 1.55f);
  const Material& zero = scene.materials[scene.materialIds[1]];  // BART's opaque 0 index reads as 1.5
  EXPECT_EQ(zero.ior, 1.5f);
  EXPECT_EQ(zero.transmission, 0.0f);
  // Two lights: summed at the first's position for the thesis rules, each kept for whitted.
  expectNear(scene.light.position, {1, 2, 3});
  expectNear(scene.light.color, glm::vec3(0.75f));
  ASSERT_EQ(scene.lights.size(), 2u);
  expectNear(scene.lights[1].position, {-1, 2, 3});
  expectNear(scene.lights[1].color, glm::vec3(0.25f));
  EXPECT_TRUE(loadAff(kAffData / "mirrors.aff").lights.empty());  // none or one light: Scene::light alone
}

TEST(AffLoader, CrlfAndCommentsAnywhere) {
  const fs::path dir = fs::temp_directory_path() / ("passtrace-aff-crlf-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "crlf.aff";
  std::ofstream(file, std::ios::binary) << "% comment\r\nm\r\n vertices 3 # trailing\r\n 0 0 0\r\n 1 0 0\r\n 0 1 0\r\n"
                                           "#fm 1 2 3\r\n triangles 1\r\n 0 1 2\r\n\r\nq\r\n";
  const std::string message = affError(file);
  EXPECT_EQ(message, file.string() + ":11: unknown command 'q'");
  fs::remove_all(dir);
}

// --- bad input -------------------------------------------------------------------

TEST(AffLoaderErrors, TruncatedFile) {
  expectError("bad_truncated.aff", 2, "unexpected end of file: expected material diffuse colour");
}
TEST(AffLoaderErrors, TruncatedMesh) {
  // Caught by the count check before any vertex is read.
  expectError("bad_truncated_mesh.aff", 2, "vertex count 4 is more than the rest of the file holds (room for at most 2)");
}
TEST(AffLoaderErrors, PolygonWithFewerVerticesThanDeclared) {
  expectError("bad_polygon_count.nff", 5, "expected vertex (a number), got 's'");
}
TEST(AffLoaderErrors, PolygonWithMoreVerticesThanDeclared) {
  expectError("bad_polygon_extra.nff", 5, "where a command should start");
}
TEST(AffLoaderErrors, VertexIndexOutOfRange) { expectError("bad_index.aff", 7, "vertex index 3 out of range (3 vertices)"); }
TEST(AffLoaderErrors, NormalIndexOutOfRange) { expectError("bad_normal_index.aff", 9, "normal index 1 out of range (1 normal)"); }
TEST(AffLoaderErrors, NaN) { expectError("bad_nan.nff", 2, "non-finite number 'nan'"); }
TEST(AffLoaderErrors, Infinity) { expectError("bad_inf.nff", 2, "non-finite number 'inf'"); }
TEST(AffLoaderErrors, BeyondFloat) { expectError("bad_huge.nff", 2, "number out of range '1e39'"); }
TEST(AffLoaderErrors, AbsurdVertexCount) { expectError("bad_absurd_count.aff", 3, "more than the rest of the file holds"); }
TEST(AffLoaderErrors, AbsurdTriangleCount) { expectError("bad_absurd_triangles.aff", 6, "more than the rest of the file holds"); }
TEST(AffLoaderErrors, NegativeCount) { expectError("bad_negative.aff", 2, "vertex count is negative"); }
TEST(AffLoaderErrors, MissingInclude) { expectError("bad_missing_include.aff", 3, "included file 'nowhere.aff' not found"); }
TEST(AffLoaderErrors, CyclicInclude) {
  // Reported where the cycle closes: in b, including a again.
  const std::string message = affError(kAffData / "bad_cycle_a.aff");
  EXPECT_EQ(message, (kAffData / "bad_cycle_b.aff").string() + ":3: cyclic include of 'bad_cycle_a.aff'");
}
TEST(AffLoaderErrors, UnclosedBlock) { expectError("bad_unclosed.aff", 9, "the '{' of line 2 is never closed"); }
TEST(AffLoaderErrors, ExtraClosingBrace) { expectError("bad_extra_brace.aff", 2, "'}' without a matching '{'"); }
TEST(AffLoaderErrors, UnknownCommand) { expectError("bad_unknown.nff", 2, "unknown command 'sphere'"); }
TEST(AffLoaderErrors, PolygonWithTwoVertices) { expectError("bad_degenerate_polygon.nff", 1, "polygon needs at least 3 vertices"); }
TEST(AffLoaderErrors, ZeroViewAngle) { expectError("bad_angle.nff", 5, "view angle must be in (0, 180)"); }
TEST(AffLoaderErrors, TruncatedKeyframes) { expectError("bad_keys_truncated.aff", 3, "key count 2 is more than"); }
TEST(AffLoaderErrors, UnclosedKeyframes) { expectError("bad_keys_unclosed.aff", 4, "unexpected end of file: expected 'transl', 'rot', 'scale' or '}'"); }
TEST(AffLoaderErrors, MissingFile) {
  const std::string message = affError(kAffData / "nothing_here.aff");
  EXPECT_EQ(message.rfind((kAffData / "nothing_here.aff").string() + ": cannot open: ", 0), 0u) << message;
}
TEST(AffLoaderErrors, Directory) {
  EXPECT_NE(affError(kAffData).find("not a regular file"), std::string::npos);
}
TEST(AffLoaderErrors, BinaryData) {
  const fs::path dir = fs::temp_directory_path() / ("passtrace-aff-bin-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "binary.aff";
  std::ofstream(file, std::ios::binary) << std::string("m\nvert\0ices", 11);
  EXPECT_EQ(affError(file), file.string() + ":2: NUL byte: binary data, not a text scene file");
  fs::remove_all(dir);
}

// --- Kochanek–Bartels and tessellation -----------------------------------------------

TEST(AffKochanekBartels, InterpolatesKeysAndHoldsTheEnds) {
  std::vector<KbKey> keys = {{0.0f, glm::vec4(0.0f)}, {1.0f, glm::vec4(1.0f)}, {3.0f, glm::vec4(-1.0f)}};
  EXPECT_EQ(evaluateKochanekBartels(keys, -5.0f), glm::vec4(0.0f));
  EXPECT_EQ(evaluateKochanekBartels(keys, 1.0f), glm::vec4(1.0f));
  EXPECT_EQ(evaluateKochanekBartels(keys, 3.0f), glm::vec4(-1.0f));
  EXPECT_EQ(evaluateKochanekBartels(keys, 9.0f), glm::vec4(-1.0f));
  // Two keys with zero TCB: the midpoint is the mean.
  const std::vector<KbKey> two = {{0.0f, glm::vec4(2.0f)}, {4.0f, glm::vec4(6.0f)}};
  EXPECT_FLOAT_EQ(evaluateKochanekBartels(two, 2.0f).x, 4.0f);
  // Tension 1 makes the tangents zero: a smoothstep between the keys.
  std::vector<KbKey> tight = two;
  for (KbKey& k : tight) k.tension = 1.0f;
  EXPECT_FLOAT_EQ(evaluateKochanekBartels(tight, 1.0f).x, 2.0f + 4.0f * (3 * 0.0625f - 2 * 0.015625f));
  EXPECT_EQ(evaluateKochanekBartels({}, 1.0f), glm::vec4(0.0f));
}

TEST(AffTessellation, CountsMatchTheDocumentedRules) {
  TriangleList list;
  tessellateSphere({0, 0, 0}, 1.0f, list);
  EXPECT_EQ(list.triangles.size(), static_cast<std::size_t>(2 * kSphereSlices * (kSphereStacks - 1)));
  list = {};
  tessellateCone({0, 0, 0}, 1.0f, {0, 1, 0}, 0.5f, list);
  EXPECT_EQ(list.triangles.size(), static_cast<std::size_t>(2 * kConeSlices));
  list = {};
  tessellateCone({0, 0, 0}, 0.0f, {0, 1, 0}, 0.5f, list);
  EXPECT_EQ(list.triangles.size(), static_cast<std::size_t>(kConeSlices));
  for (const Triangle& t : list.triangles) EXPECT_GT(glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)), 0.0f);
  list = {};
  triangulateFan({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5f, 2, 0}, {0, 1, 0}}, {}, list);
  EXPECT_EQ(list.triangles.size(), 3u);
  EXPECT_EQ(list.normals.size(), 3u);
}

// --- the BART scenes ------------------------------------------------------------------

TEST(AffBart, KitchenHasTheThesisTriangleCount) {
  const fs::path dir = bartDir();
  if (dir.empty() || !fs::exists(dir / "kitchen" / "aff" / "kitchen.aff"))
    GTEST_SKIP() << "BART scenes not found: set PASSTRACE_BART_DIR to ../shared/scenes/bart";
  SceneOptions options;
  options.bartDir = dir;
  const Scene scene = loadScene("kitchen", options);
  EXPECT_EQ(scene.name, "kitchen");
  EXPECT_EQ(scene.triangles.size(), 110561u);
  EXPECT_EQ(scene.materialIds.size(), 110561u);
  EXPECT_EQ(scene.vertexNormals.size(), 110561u);
  for (const Material& m : scene.materials) EXPECT_FALSE(m.isMirror());  // the thesis: no mirrors here
  // The camera keyframes at t = 0 (the overview); the first lamp with the six lamps' light.
  expectNear(scene.camera.eye, {3.75f, 2.3f, 3.6f});
  EXPECT_EQ(scene.camera.fovDegrees, 40.0f);
  expectNear(scene.light.position, {2.15f, 2.0f, 0.9f});
  expectNear(scene.light.color, glm::vec3(2.0f), 1e-5f);
  expectNear(scene.background, {0.5f, 0.5f, 1.0f});
  EXPECT_FLOAT_EQ(scene.ambient, 0.4f);  // am 2.5: 0.75, clamped
  const Aabb box = scene.bounds();
  EXPECT_TRUE(std::isfinite(box.min.x + box.min.y + box.min.z + box.max.x + box.max.y + box.max.z));
  // The scene number 2 is the kitchen.
  EXPECT_EQ(loadScene("2", options).triangles.size(), 110561u);
}

TEST(AffBart, RobotsHasTheThesisTriangleCount) {
  const fs::path dir = bartDir();
  if (dir.empty() || !fs::exists(dir / "robots" / "aff" / "Robot.aff"))
    GTEST_SKIP() << "BART scenes not found: set PASSTRACE_BART_DIR to ../shared/scenes/bart";
  SceneOptions options;
  options.bartDir = dir;
  const Scene scene = loadScene("1", options);
  EXPECT_EQ(scene.name, "robots");
  EXPECT_EQ(scene.triangles.size(), 71708u);
  for (const Material& m : scene.materials) EXPECT_FALSE(m.isMirror());
  expectNear(scene.camera.eye, {-3.5f, 2.0f, -203.0f});
  EXPECT_NEAR(scene.camera.fovDegrees, 36.8699f, 1e-3f);
  expectNear(scene.light.position, {1, 500, 1});
  const Aabb box = scene.bounds();
  EXPECT_TRUE(std::isfinite(box.min.x + box.min.y + box.min.z + box.max.x + box.max.y + box.max.z));
}

TEST(AffBart, MissingBartDirectorySaysWhereToLook) {
  SceneOptions options;
  options.bartDir = "/nonexistent/bart";
  try {
    loadScene("robots", options);
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("/nonexistent/bart/robots/aff/Robot.aff not found"), std::string::npos) << message;
    EXPECT_NE(message.find("PASSTRACE_BART_DIR"), std::string::npos) << message;
  }
}

TEST(AffBart, EnvironmentVariableChoosesTheDirectory) {
  const char* saved = std::getenv("PASSTRACE_BART_DIR");
  const std::string keep = saved ? saved : "";
  ::setenv("PASSTRACE_BART_DIR", "/some/where", 1);
  EXPECT_EQ(defaultBartDir(), fs::path("/some/where"));
  if (saved) ::setenv("PASSTRACE_BART_DIR", keep.c_str(), 1); else ::unsetenv("PASSTRACE_BART_DIR");
}

TEST(AffRegistry, ThesisNumbersAndNames) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"cows", "robots", "kitchen", "bunny", "cornell"}));
  EXPECT_EQ(loadScene("4").name, "cornell");
  EXPECT_EQ(loadScene("0").name, "cows");
}

}  // namespace
}  // namespace passtrace
