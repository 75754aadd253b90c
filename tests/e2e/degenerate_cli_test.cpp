// Degenerate geometry and extreme coordinates through the command line (the
// hardening issue): scenes scaled by powers of two give the unit scene's hits
// exactly, decimal and subnormal scales match brute force, coordinates that
// overflow only after a transform and empty scenes end with one clear error
// line, and zero-area-only scenes warn. Every structure on every degenerate
// scene: tests/slow/degenerate_edge_cases_test.cpp.

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/image_output.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"
#include "tests/cli_support.h"
#include "tests/degenerate_scenes.h"

namespace passtrace {
namespace {

using test::DegenerateCli;
using test::RunResult;
using test::heightField;
using test::objOf;
using test::scaledByPowerOfTwo;
using test::transformed;

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
  for (const std::string renderer : {"0", "1", "2", "3"}) {
    if (renderer == "3" && !PASSTRACE_HAVE_EMBREE) continue;  // built without Embree
    expectOneLineError(run("-s " + lightOnly + " -r " + renderer + " -w 8 -o " + path("x.png")),
                       lightOnly + ": the scene has no triangles");
  }
}

TEST_F(DegenerateCli, ZeroAreaOnlyScenesWarnAndRenderTheBackground) {
  const std::string file = write("point.obj", objOf(std::vector<Triangle>(3, Triangle{{5, 5, 5}, {5, 5, 5}, {5, 5, 5}})));
  const RunResult r = run("-s " + file + " -r 1 -b 3 -w 8 --hits " + path("h.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("every triangle has zero area"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace passtrace
