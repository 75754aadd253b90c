// Scenes beyond one texture: data spread over several textures
// (ConstInputStream pages) — the GLSL fetch against the C++ addressing, every
// GPU structure on paged data against brute force, whole renders that give
// the same bits with and without paging — the procedural scene of any size,
// and the refusal of scenes too large for the machine's memory.

#include <gtest/gtest.h>

#include <algorithm>
#include "accel/registry.h"

#include "accel/brute_force.h"
#include "accel/gpu_traversal.h"
#include "scenes/scene_registry.h"
#include "scenes/sphere_field.h"
#include "stream/const_input_stream.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"
#include "tests/cli_support.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::GlTest;

std::vector<glm::vec4> numbered(int count) {
  std::vector<glm::vec4> data;
  for (int i = 0; i < count; ++i) data.emplace_back(float(i), float(i * i), -float(i), packIndex(uint32_t(i)));
  return data;
}

// Fetches element i of `input` into pixel i of a count x 1 stream.
std::vector<glm::vec4> fetchAll(const ConstInputStream& input, int count, const std::string& pagesDefine) {
  InOutStream out(count, 1, 1);
  StreamKernel fetch("fetch", "test_functions.frag", StreamKernel::Depth::Test, {"TEST_FETCH", pagesDefine});
  fetch.bindInput("uData", input);
  fetch.set("uWidth", count);
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  fetch.execute();
  return out.read(0);
}

TEST_F(GlTest, LargestTextureIsWhatTheGlAccepts) {
  const uint32_t log2 = ConstInputStream::largestPageLog2();
  GLint side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
  EXPECT_GE(log2, 20u);  // every GL 4.5 allows 1024 x 1024 RGBA32F
  EXPECT_LE(uint64_t(1) << log2, uint64_t(side) * uint64_t(side));
  std::cout << "largest page: 2^" << log2 << " RGBA32F texels (" << ((uint64_t(16) << log2) >> 20) << " MiB)\n";
}

TEST_F(GlTest, PagedFetchMatchesCppAddressing) {
  const std::vector<glm::vec4> data = numbered(37);
  for (uint64_t pageTexels : {8u, 16u, 5u /* rounds down to 4: 10 pages */}) {
    if (pageTexels == 5u) {
      EXPECT_THROW(ConstInputStream(data, "test data", pageTexels), GlError);
      continue;
    }
    ConstInputStream input(data, "test data", pageTexels);
    ASSERT_EQ(input.pageCount(), (37 + pageTexels - 1) / pageTexels);
    EXPECT_EQ(uint64_t(1) << input.pageLog2(), pageTexels);
    const std::vector<glm::vec4> result = fetchAll(input, 37, streamPagesDefine({&input}));
    for (int i = 0; i < 37; ++i) EXPECT_EQ(result[i], data[i]) << "texel " << i << ", pages of " << pageTexels;
  }
}

TEST_F(GlTest, TooManyPagesIsAnErrorNamingTheData) {
  try {
    ConstInputStream input(numbered(100), "the test sequence", 8);
    FAIL() << "13 pages accepted";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("the test sequence"), std::string::npos) << e.what();
  }
}

TEST_F(GlTest, KernelCompiledForFewerPagesRefusesPagedData) {
  ConstInputStream input(numbered(37), "test data", 8);
  StreamKernel fetch("fetch", "test_functions.frag", StreamKernel::Depth::Test, {"TEST_FETCH", "STREAM_PAGES 2"});
  EXPECT_THROW(fetch.bindInput("uData", input), GlError);
}

// Every GPU structure with its data split into several textures finds the
// brute-force hits. The page size starts where the triangles alone take four
// pages and doubles until no stream needs more than kMaxStreamPages, so the
// largest stream of each structure is paged.
// Parametrised by the registry's stream structures.
std::vector<std::string> streamStructureNames() {
  std::vector<std::string> names;
  for (const Structure& s : structures())
    if (s.runsOn(RendererId::Gpu)) names.emplace_back(s.name);
  return names;
}

class PagedTraversal : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(PagedTraversal, SameHitsAsBruteForce) {
  const std::vector<Triangle> tris = testmesh::uvSphere(24, 32);
  Scene scene;
  scene.triangles = tris;
  scene.materialIds.assign(tris.size(), 0);
  scene.materials = {Material{}};
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 7);
  std::unique_ptr<GpuTraversal> traversal;
  for (uint64_t page = std::bit_ceil(3 * tris.size() / 4); !traversal; page *= 2) {
    ASSERT_LT(page, 1u << 24) << "no page size worked";
    try {
      traversal = makeStreamStructure(GetParam(), scene.triangles, GpuTraversalConfig{{}, 16, GridKernels::Merged, page});
    } catch (const GlError& e) {
      ASSERT_NE(std::string(e.what()).find("a kernel reads at most"), std::string::npos) << e.what();
    }
  }
  const test::TracedRays gpu = test::traceOnGpu(*traversal, rays);
  size_t found = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit brute = intersectBruteForce(tris, rays[i], false);
    const Hit& h = gpu.hits[i];
    ASSERT_EQ(h.found(), brute.found()) << "ray " << i;
    if (h.found() && h.id != brute.id) { EXPECT_NEAR(h.t, brute.t, 1e-5f * std::max(1.0f, brute.t)) << "ray " << i; }
    found += brute.found();
  }
  EXPECT_GT(found, rays.size() / 10);
}

INSTANTIATE_TEST_SUITE_P(AllStructures, PagedTraversal, ::testing::ValuesIn(streamStructureNames()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// Whole frames (three bounces on the Cornell box, whose mirror and shadows
// read the shading data at every bounce) give the same bits with 64-texel
// pages and 3 steps per pass as with one texture per stream and 20 steps.
using Cli = test::CliTest;

TEST_F(Cli, PagedDataRendersTheSameBits) {
  for (const std::string accel : {"kk-bvh", "kd-restart", "kd-backtrack", "grid", "grid --grid-kernels split"}) {
    SCOPED_TRACE(accel);
    const std::string common = "-s cornell -r 2 -w 40 -b 3 -a " + accel;
    ASSERT_EQ(run(common + " -o " + path("one.exr") + " --hits " + path("one-hits.exr")).status, 0);
    const test::RunResult paged =
        run(common + " --page-texels 64 -l 3 -o " + path("paged.exr") + " --hits " + path("paged-hits.exr"));
    ASSERT_EQ(paged.status, 0) << paged.err;
    EXPECT_EQ(test::slurp(path("one.exr")), test::slurp(path("paged.exr")));
    EXPECT_EQ(test::slurp(path("one-hits.exr")), test::slurp(path("paged-hits.exr")));
  }
}

// The procedural scene of any size: exactly the promised count, at least the
// requested one, the same triangles on every call.
TEST(SphereField, CountIsPredictedAndDeterministic) {
  for (uint64_t requested : {1000ull, 123456ull}) {
    const Scene a = makeSphereField(requested), b = makeSphereField(requested);
    EXPECT_EQ(a.triangles.size(), sphereFieldTriangles(requested));
    EXPECT_GE(a.triangles.size(), requested);
    EXPECT_LT(a.triangles.size(), requested * 5 / 4 + 2400);  // about the next finer tessellation
    ASSERT_EQ(a.materialIds.size(), a.triangles.size());
    for (size_t i = 0; i < a.triangles.size(); i += 997) {
      EXPECT_EQ(a.triangles[i].v0, b.triangles[i].v0);
      EXPECT_EQ(a.triangles[i].v2, b.triangles[i].v2);
    }
  }
}

// A GPU render of the procedural scene with its data in several textures
// against brute force, through the command line.
TEST_F(Cli, PagedSpheresHitsEqualBruteForce) {
  SceneOptions options;
  options.triangles = 20000;
  const Scene scene = loadScene("spheres", options);
  const test::RunResult r =
      run("-s spheres --triangles 20000 -r 2 -a 0 -b 1 -w 40 --page-texels 32768 --hits " + path("h.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  test::expectHitsMatchBruteForce(path("h.exr"), scene, 40);
}

// A scene that cannot fit is refused before anything is built.
TEST_F(Cli, SceneTooLargeForMemoryIsRefusedBeforeBuilding) {
  const std::string outs = " -o " + path("x.png") + " --hits " + path("x.exr");
  expectOneLineError(run("-s spheres --triangles 400000000 -r 2 -a grid" + outs), "nothing was built");
  expectOneLineError(run("-s spheres --triangles 400000000 -r 1 -a kd-pbrt" + outs), "GiB available");
  expectOneLineError(run("-s spheres --triangles 999" + outs), "--triangles");
}

}  // namespace
}  // namespace passtrace
