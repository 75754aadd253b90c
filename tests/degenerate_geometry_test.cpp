// Degenerate geometry and extreme coordinates (the hardening issue): one
// triangle, all triangles in one plane or one point, zero-area and duplicate
// triangles, a scene far from the origin, enormous, tiny, near-FLT_MAX and
// subnormal coordinates, coordinates that overflow only after a transform,
// and empty scenes. Every case either renders the same hits as brute force
// on every structure of every renderer or ends with one clear error line.

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/brute_force.h"
#include "accel/cpu_accelerator.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/stream_mirror_accelerators.h"
#include "render/camera.h"
#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"
#include "accel/gpu_traversal.h"
#include "render/image_output.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"
#include "tests/cli_support.h"
#include "tests/gl_test_support.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

using test::RunResult;

// Every structure of every ray tracer, as the command line names them.
const std::vector<std::pair<int, std::string>> kEveryStructure = {
    {2, "kk-bvh"},           {2, "gs-bvh"},           {2, "kd-restart"}, {2, "kd-backtrack"}, {2, "grid"},
    {2, "grid --grid-kernels split"}, {1, "kk-bvh"},  {1, "gs-bvh"},     {1, "kd-tree"},      {1, "kd-pbrt"},
    {1, "grid"},             {1, "kk-bvh-recursive"}, {1, "gs-bvh-recursive"}, {1, "octree"}, {1, "kd-restart"},
    {1, "kd-backtrack"},     {1, "grid-stream"},      {3, "0"}};

// An OBJ of separate triangles, every coordinate written exactly (%.17g of a
// float is its exact value, so the file reads back bit for bit).
std::string objOf(const std::vector<Triangle>& tris) {
  std::string text;
  char line[160];
  for (const Triangle& t : tris)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", double(v.x), double(v.y), double(v.z));
      text += line;
    }
  for (size_t i = 0; i < tris.size(); ++i) text += "f " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
  return text;
}

// An n x n height field over [-1, 1]^2 in the plane z = 0 when bumpy is
// false (a flat square of 2n^2 triangles), with hills otherwise.
std::vector<Triangle> heightField(int n, bool bumpy) {
  const auto at = [&](int i, int j) {
    const float x = -1.0f + 2.0f * float(i) / float(n), y = -1.0f + 2.0f * float(j) / float(n);
    return glm::vec3(x, y, bumpy ? 0.3f * std::sin(3.0f * x) * std::cos(2.0f * y) : 0.0f);
  };
  std::vector<Triangle> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      tris.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return tris;
}

std::vector<Triangle> transformed(std::vector<Triangle> tris, const std::function<glm::vec3(glm::vec3)>& f) {
  for (Triangle& t : tris) t = {f(t.v0), f(t.v1), f(t.v2)};
  return tris;
}

std::vector<Triangle> scaledByPowerOfTwo(std::vector<Triangle> tris, int k) {
  return transformed(std::move(tris), [k](glm::vec3 v) { return scaleByPowerOfTwo(v, k); });
}

// The degenerate scenes, each with the fraction of pixels that must hit.
struct EdgeCase {
  const char* name;
  std::vector<Triangle> tris;
  double minFound;
};

std::vector<EdgeCase> edgeCases() {
  std::vector<EdgeCase> cases;
  cases.push_back({"one_triangle", {{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}, 0.2});
  cases.push_back({"axis_plane", heightField(4, false), 0.2});
  // The same square tilted about two axes: flat, but in no axis plane.
  cases.push_back({"oblique_plane",
                   transformed(heightField(4, false),
                               [](glm::vec3 v) { return glm::vec3(v.x, 0.6f * v.y, 0.8f * v.y + 0.5f * v.x); }),
                   0.1});
  // Zero-area triangles with zero-extent bounds: nothing can be hit.
  cases.push_back({"one_point", std::vector<Triangle>(5, Triangle{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}), 0.0});
  // Collinear, repeated-vertex and point triangles among normal ones.
  std::vector<Triangle> mixed = heightField(3, true);
  for (int i = 0; i < 6; ++i) {
    const float s = -1.0f + 0.4f * float(i);
    mixed.insert(mixed.begin() + 2 * i, Triangle{{s, -1, 0.1f}, {s + 0.1f, 0, 0.1f}, {s + 0.2f, 1, 0.1f}});
    mixed.push_back(Triangle{{s, s, 0.2f}, {s, s, 0.2f}, {0.5f, 0.5f, 0.2f}});
    mixed.push_back(Triangle{{s, 0, 0}, {s, 0, 0}, {s, 0, 0}});
  }
  // Every normal triangle twice, one three times: ties at equal t.
  const std::vector<Triangle> normal = heightField(3, true);
  mixed.insert(mixed.end(), normal.begin(), normal.end());
  mixed.push_back(normal[4]);
  cases.push_back({"zero_area_and_duplicates", mixed, 0.2});
  cases.push_back({"far_from_origin",
                   transformed(heightField(3, true), [](glm::vec3 v) { return v + glm::vec3(1e6f, -2e6f, 3e6f); }),
                   0.2});
  return cases;
}

class DegenerateCli : public test::CliTest {
 protected:
  // Inputs go to a subdirectory, apart from the outputs that must not appear.
  std::string write(const std::string& name, const std::string& text) {
    fs::create_directories(dir_ / "in");
    const fs::path file = dir_ / "in" / name;
    std::ofstream(file) << text;
    return file.string();
  }
};

// Every degenerate scene through every structure of every renderer: the
// primary hits equal brute force, with three bounces traced behind them
// (shadow rays and shading must cope as well), and the preview renders.
TEST_F(DegenerateCli, EdgeCaseScenesMatchBruteForceOnEveryStructure) {
  for (const EdgeCase& c : edgeCases()) {
    const std::string file = write(std::string(c.name) + ".obj", objOf(c.tris));
    const Scene scene = loadScene(file);
    ASSERT_EQ(scene.triangles.size(), c.tris.size());
    for (const auto& [renderer, accel] : kEveryStructure) {
      if (renderer == 3 && !PASSTRACE_HAVE_EMBREE) continue;  // built without Embree
      SCOPED_TRACE(std::string(c.name) + " -r " + std::to_string(renderer) + " -a " + accel);
      const RunResult r = run("-s " + file + " -b 3 -w 12 -t 1 -r " + std::to_string(renderer) + " -a " + accel +
                              " --hits " + path("h.exr"));
      ASSERT_EQ(r.status, 0) << r.err;
      // Embree's own triangle test rounds differently from Möller–Trumbore:
      // a ray passing within rounding error (0.25 units at 3e6) of an edge
      // may take the neighbouring triangle or miss (4 of 144 pixels here).
      const int allowed = renderer == 3 && std::string(c.name) == "far_from_origin" ? 8 : 0;
      test::expectHitsMatchBruteForce(path("h.exr"), scene, 12, 12, c.minFound, allowed);
    }
    const RunResult preview = run("-s " + file + " -r 0 -w 12 -o " + path("p.png"));
    EXPECT_EQ(preview.status, 0) << c.name << ": " << preview.err;
    EXPECT_TRUE(fs::exists(path("p.png"))) << c.name;
    fs::remove(path("p.png"));
  }
}

// The hit buffer of a scene scaled by 2^k equals the unit scene's with every
// t multiplied by 2^k exactly, and the same ids: loadScene rescales it back.
TEST_F(DegenerateCli, ExtremeScalesGiveTheUnitScalesHitsExactly) {
  const std::vector<Triangle> unit = heightField(6, true);
  const auto hitsOf = [&](const std::string& name, const std::vector<Triangle>& tris, const std::string& args) {
    const std::string file = write(name + ".obj", objOf(tris));
    const RunResult r = run("-s " + file + " -b 3 -w 16 --hits " + path(name + ".exr") + " " + args);
    EXPECT_EQ(r.status, 0) << r.err;
    int w = 0, h = 0;
    return std::make_pair(readHitBuffer(path(name + ".exr"), w, h), r.err);
  };
  // The rescaled scene is bit for bit the unit one, so one structure per
  // scale suffices; 2^126 puts coordinates near FLT_MAX (the extent
  // overflows to inf).
  const std::vector<std::pair<std::string, std::vector<int>>> runs = {{"-r 2 -a kd-backtrack", {-100, 126}},
                                                                     {"-r 1 -a grid", {-60, 30, 100}}};
  for (const auto& [args, exponents] : runs) {
    SCOPED_TRACE(args);
    const auto [reference, referenceErr] = hitsOf("unit", unit, args);
    EXPECT_EQ(referenceErr, "");
    int found = 0;
    for (const HitRecord& h : reference) found += h.id != kNoHit;
    EXPECT_GT(found, 16 * 16 / 5);
    for (int k : exponents) {
      SCOPED_TRACE("2^" + std::to_string(k));
      const auto [hits, err] = hitsOf("scaled" + std::to_string(k), scaledByPowerOfTwo(unit, k), args);
      EXPECT_EQ(err, "");
      ASSERT_EQ(hits.size(), reference.size());
      for (size_t i = 0; i < hits.size(); ++i) {
        EXPECT_EQ(hits[i].id, reference[i].id) << "pixel " << i;
        EXPECT_EQ(hits[i].t, std::ldexp(reference[i].t, k)) << "pixel " << i;
      }
    }
  }
}

// Decimal scales (not exact) and subnormal coordinates (fewer bits, with a
// warning) against brute force; --eye and --look-at stay in the file's units.
TEST_F(DegenerateCli, DecimalAndSubnormalScalesMatchBruteForce) {
  const std::vector<Triangle> unit = heightField(6, true);
  const std::pair<float, const char*> runs[] = {{1e-30f, "-r 2 -a gs-bvh"}, {1e-20f, "-r 1 -a kd-tree"},
                                                {1e10f, "-r 2 -a grid"},      {1e20f, "-r 1 -a octree"},
                                                {1e30f, "-r 3"},              {1e-40f, "-r 2 -a kd-restart"}};
  for (const auto& [s, args] : runs) {
    if (std::string(args) == "-r 3" && !PASSTRACE_HAVE_EMBREE) continue;  // built without Embree
    SCOPED_TRACE(std::to_string(s) + " " + args);
    const std::string file = write("s.obj", objOf(transformed(unit, [s = s](glm::vec3 v) { return v * s; })));
    const Scene scene = loadScene(file);
    const RunResult r = run("-s " + file + " -b 3 -w 16 --hits " + path("h.exr") + " " + args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("subnormal") != std::string::npos, s < FLT_MIN) << r.err;
    test::expectHitsMatchBruteForce(path("h.exr"), scene, 16, 16, 0.2);
    // The scene's own view given on the command line, in the file's units
    // (not for subnormal ones: the eye would lose bits in them).
    if (s < FLT_MIN) continue;
    const glm::vec3 eye = scaleByPowerOfTwo(scene.camera.eye, -scene.scaleExponent);
    const glm::vec3 at = scaleByPowerOfTwo(scene.camera.lookAt, -scene.scaleExponent);
    char view[200];
    std::snprintf(view, sizeof view, " --eye %.9g,%.9g,%.9g --look-at %.9g,%.9g,%.9g", double(eye.x), double(eye.y),
                  double(eye.z), double(at.x), double(at.y), double(at.z));
    const RunResult withView = run("-s " + file + " -b 1 -w 16 -r 1 --hits " + path("h.exr") + view);
    ASSERT_EQ(withView.status, 0) << withView.err;
    test::expectHitsMatchBruteForce(path("h.exr"), scene, 16, 16, 0.2);
  }
}

// The non-finite rule (scenes/scene.h): finite numbers that overflow in a
// transform or a tessellation are rejected naming the file and the line.
TEST_F(DegenerateCli, VerticesOverflowingInTransformsAreRejectedWithFileAndLine) {
  const std::string triangle = "p 3\n0 0 0\n1e9 0 0\n0 1e9 0\n";
  const std::string aff1 = write("scale.aff", "xs 1e30 1e30 1e30 0 0 1 0 0 0 0 {\n" + triangle + "}\n");
  expectOneLineError(run("-s " + aff1 + " -w 8"), aff1 + ":2: non-finite vertex after the transforms");
  const std::string aff2 = write("nested.aff",
                                 "xs 1e20 1e20 1e20 0 0 1 0 0 0 0 {\n"
                                 "xs 1e20 1e20 1e20 0 0 1 0 0 0 0 {\n"
                                 "b 0 0 0\n" +
                                     triangle + "}\n}\n");
  expectOneLineError(run("-s " + aff2 + " -w 8"), aff2 + ":4: non-finite vertex after the transforms");
  const std::string nff = write("sphere.nff", "b 0 0 0\ns 3e38 0 0 3e38\n");
  expectOneLineError(run("-s " + nff + " -w 8"), nff + ":2: non-finite vertex after tessellation");

  // One triangle (0,0,0) (1,0,0) (0,1,0); NODES is the node list, mesh on the last.
  const auto gltf = [&](const std::string& name, const std::string& nodes) {
    return write(name,
                 R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
                     R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                     R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
                     R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],)"
                     R"("accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":3,"min":[0,0,0],"max":[1,1,0]}]})");
  };
  const std::string product = gltf("product.gltf", R"([{"scale":[1e30,1e30,1e30],"children":[1]},{"scale":[1e30,1e30,1e30],"mesh":0}])");
  expectOneLineError(run("-s " + product + " -w 8"), product + ": node 1: transform is not finite");
  // Only an off-diagonal entry overflows (a shear of 3e38 applied twice).
  const std::string shear = R"({"matrix":[1,0,0,0, 3e38,1,0,0, 0,0,1,0, 0,0,0,1])";
  const std::string offDiagonal = gltf("shear.gltf", "[" + shear + R"(,"children":[1]},)" + shear + R"(,"mesh":0}])");
  expectOneLineError(run("-s " + offDiagonal + " -w 8"), offDiagonal + ": node 1: transform is not finite");
  // A finite matrix that carries a finite vertex past FLT_MAX.
  const std::string carry = gltf("carry.gltf", R"([{"translation":[3e38,0,0],"scale":[3e38,1,1],"mesh":0}])");
  expectOneLineError(run("-s " + carry + " -w 8"), carry + ": mesh 0 primitive 0: non-finite vertex after the node transforms");
}

// Empty scenes are refused with one line (the rule: an empty file is a
// failed export far more often than a wish to render the background).
TEST_F(DegenerateCli, EmptyScenesAreRefusedWithOneLine) {
  const std::string vertices = write("vertices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expectOneLineError(run("-s " + vertices + " -w 8 -o " + path("x.png")), vertices + ": no triangles");
  const std::string lightOnly = write("light.nff", "l 1 2 3\nb 0.1 0.2 0.3\n");
  for (const char* renderer : {"0", "1", "2", "3"})
    expectOneLineError(run("-s " + lightOnly + " -r " + renderer + " -w 8 -o " + path("x.png")),
                       lightOnly + ": the scene has no triangles");
}

TEST_F(DegenerateCli, ZeroAreaOnlyScenesWarnAndRenderTheBackground) {
  const std::string file = write("point.obj", objOf(std::vector<Triangle>(3, Triangle{{5, 5, 5}, {5, 5, 5}, {5, 5, 5}})));
  const RunResult r = run("-s " + file + " -r 1 -b 3 -w 8 --hits " + path("h.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("every triangle has zero area"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// The rescaling rule itself: only scenes outside [2^-16, 2^16] move, by the
// power of two that brings their largest coordinate into [1, 2), exactly.
TEST(SceneScale, RescalesOnlyOutsideTheSafeRangeAndExactly) {
  Scene scene;
  scene.triangles = heightField(2, true);
  EXPECT_EQ(sceneScaleExponent(scene), 0);
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 16);
  EXPECT_EQ(sceneScaleExponent(scene), 0) << "2^16 is still in range";
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 17);
  EXPECT_EQ(sceneScaleExponent(scene), -17);
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), -17);
  EXPECT_EQ(sceneScaleExponent(scene), 17);
  scene.triangles.assign(2, Triangle{});  // all at the origin
  EXPECT_EQ(sceneScaleExponent(scene), 0);

  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 90);
  scene.camera.eye = {0, 0, std::ldexp(3.0f, 90)};
  scene.light.position = {std::ldexp(1.0f, 91), 0, 0};
  EXPECT_EQ(normalizeSceneScale(scene), -90);
  EXPECT_EQ(scene.scaleExponent, -90);
  const std::vector<Triangle> unit = heightField(2, true);
  for (size_t i = 0; i < unit.size(); ++i) EXPECT_EQ(scene.triangles[i].v1, unit[i].v1);
  EXPECT_EQ(scene.camera.eye, glm::vec3(0, 0, 3));
  EXPECT_EQ(scene.light.position, glm::vec3(2, 0, 0));
}

// Framing a scene in one point, near FLT_MAX or of subnormal size still gives
// a usable, finite view (scene_registry.cpp).
TEST(SceneScale, FramingCopesWithPointsAndExtremeBounds) {
  for (const Aabb& box : {Aabb{{1e30f, 1e30f, 1e30f}, {1e30f, 1e30f, 1e30f}}, Aabb{{-3e38f, -3e38f, 0}, {3e38f, 3e38f, 0}},
                          Aabb{{1e-40f, 0, 0}, {3e-40f, 1e-40f, 0}}, Aabb{{2, 2, 2}, {2, 2, 2}}}) {
    const CameraSpec c = framedCamera(box);
    EXPECT_NE(c.eye, c.lookAt) << box.min.x;
    EXPECT_TRUE(std::isfinite(c.lookAt.x + c.lookAt.y + c.lookAt.z)) << box.min.x;
  }
}

// The structures themselves with no triangles at all (the command line
// refuses empty scenes before building, but a library caller may not):
// every ray misses, nothing crashes.
class EmptyStructures : public test::GlTest {};

TEST_F(EmptyStructures, EveryStructureBuildsAndMissesWithoutTriangles) {
  Scene scene;
  scene.materials.push_back(Material{});
  std::vector<Ray> rays;
  for (int i = 0; i < 16; ++i) rays.push_back(Ray{{0, 0, 3}, glm::normalize(glm::vec3(0.1f * float(i - 8), 0.05f, -1))});
  AccelBuildConfig build;
  build.gsTries = 1;
  for (int number = 0; number < 8; ++number) {
    SCOPED_TRACE("CPU " + std::to_string(number));
    const auto accel = makeCpuAccelerator(number, scene.triangles, build);
    for (const Ray& ray : rays) EXPECT_FALSE(accel->intersect(ray, false, nullptr).found());
  }
  for (const char* name : {"kd-restart", "kd-backtrack", "grid-stream"}) {
    SCOPED_TRACE(name);
    const auto accel = makeStreamMirrorAccelerator(*streamMirrorByName(name), scene.triangles, build);
    for (const Ray& ray : rays) EXPECT_FALSE(accel->intersect(ray, false, nullptr).found());
  }
  if (PASSTRACE_HAVE_EMBREE) {
    const auto embree = makeEmbreeAccelerator(scene.triangles);
    for (const Ray& ray : rays) EXPECT_FALSE(embree->intersect(ray, false, nullptr).found());
  }
  for (int number = 0; number < 5; ++number)
    for (const GridKernels kernels : {GridKernels::Merged, GridKernels::Split}) {
      if (number != 4 && kernels == GridKernels::Split) continue;
      SCOPED_TRACE("GPU " + std::to_string(number));
      const auto traversal = makeGpuTraversal(number, scene, GpuTraversalConfig{build, 20, kernels});
      for (const Hit& hit : test::traceOnGpu(*traversal, rays).hits) EXPECT_FALSE(hit.found());
    }
}

}  // namespace
}  // namespace passtrace

namespace passtrace {
namespace {

// The measurement behind scene_scale.h (run with
// --gtest_also_run_disabled_tests): the bunny scaled by 1e-30 ... 1e30 through
// every structure, without ("raw": loadObj and framing only) and with
// loadScene's rescaling, against the unit bunny's hits on the same
// structure. Prints the pixels (of 32x32) whose hit differs.
class ScaleMeasurement : public test::GlTest {};

std::vector<HitRecord> primaryHits(const Scene& scene, int renderer, const std::string& accel, int size) {
  AccelBuildConfig build;
  build.gsTries = 1;
  if (renderer == 2) {
    const auto traversal = makeGpuTraversal(gpuAcceleratorNumber(accel), scene, GpuTraversalConfig{build, 20});
    GpuRenderer gpu(scene, *traversal, size, size);
    return gpu.render(scene.camera, 1, true).primaryHits;
  }
  const auto mirror = streamMirrorByName(accel);
  const auto cpuAccel = renderer == 3 ? makeEmbreeAccelerator(scene.triangles)
                        : mirror      ? makeStreamMirrorAccelerator(*mirror, scene.triangles, build)
                                      : makeCpuAccelerator(acceleratorNumber(accel), scene.triangles, build);
  CpuRenderer cpu(scene, *cpuAccel, 0);
  return cpu.render(scene.camera, size, size, 1, true).primaryHits;
}

TEST_F(ScaleMeasurement, DISABLED_ScaledBunnyAgainstUnitBunny) {
  const fs::path bunny = "/usr/share/glmark2/models/bunny.obj";
  if (!fs::exists(bunny)) GTEST_SKIP() << "no bunny";
  const Scene unit = loadObj(bunny);
  const int size = 32;
  const double scales[] = {1e-30, 1e-20, 1e-10, 1e10, 1e18, 1e20, 1e30};
  std::printf("| renderer | structure |");
  for (double s : scales) std::printf(" %g raw | %g rescaled |", s, s);
  std::printf("\n");
  for (const auto& [renderer, accel] : kEveryStructure) {
    if (accel.find("split") != std::string::npos) continue;
    if (renderer == 3 && !PASSTRACE_HAVE_EMBREE) continue;  // built without Embree
    Scene reference = unit;
    reference.camera = framedCamera(reference.bounds());
    const std::vector<HitRecord> expected = primaryHits(reference, renderer, accel, size);
    std::printf("| %d | %s |", renderer, accel.c_str());
    for (double s : scales) {
      Scene raw = unit;
      for (Triangle& t : raw.triangles) t = {t.v0 * float(s), t.v1 * float(s), t.v2 * float(s)};
      raw.camera = framedCamera(raw.bounds());
      raw.light = framedLight(raw.bounds());
      Scene rescaled = raw;
      normalizeSceneScale(rescaled);
      for (const Scene* scene : {&raw, &rescaled}) {
        std::vector<HitRecord> got;
        try {
          got = primaryHits(*scene, renderer, accel, size);
        } catch (const std::exception& e) {
          std::printf(" error: %s |", e.what());
          continue;
        }
        int wrong = 0;
        for (size_t i = 0; i < got.size(); ++i) {
          const double t = std::ldexp(double(got[i].t), -scene->scaleExponent) / s;
          const bool same = got[i].id == expected[i].id ||
                            (got[i].id != kNoHit && expected[i].id != kNoHit && std::abs(t - expected[i].t) <= 1e-4 * expected[i].t);
          wrong += !same || (got[i].id != kNoHit && !(std::abs(t - expected[i].t) <= 1e-4 * expected[i].t));
        }
        std::printf(" %d |", wrong);
      }
      std::fflush(stdout);
    }
    std::printf("\n");
  }
}

}  // namespace
}  // namespace passtrace
