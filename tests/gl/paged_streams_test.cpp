// Scenes beyond one texture: data spread over several textures
// (ConstInputStream pages) — the GLSL fetch against the C++ addressing, and
// every GPU structure of the registry on paged data against brute force.
// Whole renders with paged data: tests/e2e/paged_cli_test.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <bit>
#include <memory>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/gpu_traversal.h"
#include "accel/registry.h"
#include "scenes/scene.h"
#include "stream/const_input_stream.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

using test::GlTest;

std::vector<glm::vec4> numbered(int count) {
  std::vector<glm::vec4> data;
  for (int i = 0; i < count; ++i) data.emplace_back(float(i), float(i * i), -float(i), packIndex(uint32_t(i)));
  return data;
}

// Fetches element i of `input` into pixel i of a count x 1 stream, read as a
// ConstStream (`pagesDefine` STREAM_PAGES) or, with a LARGE_STREAM_PAGES
// define, as a LargeConstStream.
std::vector<glm::vec4> fetchAll(const ConstInputStream& input, int count, const std::string& pagesDefine) {
  InOutStream out(count, 1, 1);
  const bool large = pagesDefine.starts_with("LARGE_");
  StreamKernel fetch("fetch", "test_functions.frag", StreamKernel::Depth::Test,
                     {large ? "TEST_FETCH_LARGE" : "TEST_FETCH", pagesDefine});
  fetch.bindInput(large ? "uLargeData" : "uData", input);
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

// Written in pieces (bvh-octant's sequences go up octant by octant): pieces of
// 1 to 5 texels, last first, crossing rows and pages, read back as the data;
// a write past the end is an error naming the data.
TEST_F(GlTest, StreamWrittenInPiecesReadsBackAsTheData) {
  const std::vector<glm::vec4> data = numbered(37);
  for (uint64_t pageTexels : {0u, 8u, 16u}) {
    ConstInputStream input(data.size(), "test data", pageTexels);
    for (size_t end = data.size(); end > 0;) {
      const size_t count = std::min(end, end % 5 + 1);
      input.write(end - count, std::span<const glm::vec4>(data).subspan(end - count, count));
      end -= count;
    }
    const std::vector<glm::vec4> result = fetchAll(input, 37, streamPagesDefine({&input}));
    for (int i = 0; i < 37; ++i) EXPECT_EQ(result[i], data[i]) << "texel " << i << ", pages of " << pageTexels;
  }
  ConstInputStream small(4, "the small stream");
  try {
    small.write(3, std::span<const glm::vec4>(data).first(2));
    ADD_FAILURE() << "a write past the end was accepted";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("the small stream"), std::string::npos) << e.what();
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

// A kernel's one large stream (bvh-octant's sequences) may have more pages
// than its others, up to kMaxLargeStreamPages, each read where C++ puts it.
TEST_F(GlTest, LargeStreamHasMorePagesThanOthers) {
  const std::vector<glm::vec4> data = numbered(60);
  EXPECT_THROW(ConstInputStream(data, "test data", 4), GlError);  // 15 pages
  EXPECT_THROW(ConstInputStream(data, "test data", 2, kMaxLargeStreamPages), GlError);  // 30 pages
  ConstInputStream input(data, "test data", 4, kMaxLargeStreamPages);
  ASSERT_EQ(input.pageCount(), 15u);
  ASSERT_GT(input.pageCount(), kMaxStreamPages);
  const std::vector<glm::vec4> result = fetchAll(input, 60, largeStreamPagesDefine(input));
  for (int i = 0; i < 60; ++i) EXPECT_EQ(result[i], data[i]) << "texel " << i;
  // The kernel's other streams keep their own STREAM_PAGES: read as one of those, the data is refused.
  StreamKernel fetch("fetch", "test_functions.frag", StreamKernel::Depth::Test,
                     {"TEST_FETCH", "STREAM_PAGES 8", largeStreamPagesDefine(input)});
  EXPECT_THROW(fetch.bindInput("uData", input), GlError);
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

INSTANTIATE_TEST_SUITE_P(AllStructures, PagedTraversal,
                         ::testing::ValuesIn(testing_registry::rowNames(RendererId::Gpu)),
                         testing_registry::CaseNameOfRow());

}  // namespace
}  // namespace passtrace
