// Per-pass kernel tests: each kernel runs on a few hand-built stream elements
// and its output is compared with the same computation in C++.

#include <random>

#include <gtest/gtest.h>

#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "render/camera.h"
#include "render/gpu_renderer.h"
#include "accel/bvh/gpu_bvh_traversal.h"
#include "accel/ray_stream_layout.h"
#include "render/scene_streams.h"
#include "render/shading.h"
#include "stream/const_input_stream.h"
#include "stream/gl_error.h"
#include "stream/storage_buffer.h"
#include "stream/texel_address.h"
#include "tests/gl_test_support.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::GlTest;

TEST(TexelAddress, MatchesRowMajorLayoutOfPowerOfTwoWidth) {
  EXPECT_EQ(ConstInputStream::chooseWidthLog2(1), 0u);
  EXPECT_EQ(ConstInputStream::chooseWidthLog2(5), 2u);   // 4x4 holds 5
  EXPECT_EQ(ConstInputStream::chooseWidthLog2(16), 2u);  // 4x4 holds 16
  EXPECT_EQ(ConstInputStream::chooseWidthLog2(17), 3u);
  const TexelCoord c = texelOf(19, 3);
  EXPECT_EQ(c.x, 3u);
  EXPECT_EQ(c.y, 2u);
  for (uint32_t i : {0u, 1u, 1u << 24, (1u << 24) + 1, 0x7EFFFFFFu}) EXPECT_EQ(unpackIndex(packIndex(i)), i);
  EXPECT_GT(packIndex(0), 0.0f);  // packed indices are positive normal floats
  EXPECT_TRUE(std::isnormal(packIndex(0)));
}

TEST_F(GlTest, ConstInputStreamFetchMatchesCppAddressing) {
  // 37 texels: a 8-wide texture with a partial last row.
  std::vector<glm::vec4> data;
  for (int i = 0; i < 37; ++i) data.emplace_back(float(i), float(i * i), -float(i), packIndex(uint32_t(i)));
  ConstInputStream input(data, "test data");
  EXPECT_EQ(input.widthLog2(), 3u);
  InOutStream out(37, 1, 1);
  StreamKernel fetch("fetch", "test_functions.frag", StreamKernel::Depth::Test, {"TEST_FETCH"});
  fetch.bindInput("uData", input);
  fetch.set("uWidth", 37);
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  fetch.execute();
  const std::vector<glm::vec4> result = out.read(0);
  for (int i = 0; i < 37; ++i) {
    EXPECT_EQ(result[i], data[i]) << "texel " << i;
    EXPECT_EQ(unpackIndex(result[i].w), uint32_t(i));
  }
}

// The kd short-stack kernels keep their stacks in a storage buffer across
// passes: three passes each add element + 1, so anything but 3 (element + 1)
// means a pass lost or did not see the previous pass's writes.
TEST_F(GlTest, StorageBufferWritesPersistAcrossPasses) {
  constexpr int kWidth = 13, kHeight = 5;
  StorageBuffer buffer("test storage");
  buffer.reserve(kWidth * kHeight);
  EXPECT_EQ(buffer.read(kWidth * kHeight), std::vector<float>(kWidth * kHeight, 0.0f));  // starts zeroed
  InOutStream out(kWidth, kHeight, 1);
  StreamKernel add("add", "test_functions.frag", StreamKernel::Depth::Test, {"TEST_STORAGE"});
  add.bindStorage(0, buffer);
  add.set("uWidth", kWidth);
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  for (int pass = 0; pass < 3; ++pass) add.execute();
  const std::vector<glm::vec4> result = out.read(0);
  const std::vector<float> stored = buffer.read(kWidth * kHeight);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    EXPECT_EQ(result[i].x, 3.0f * float(i + 1)) << "element " << i;
    EXPECT_EQ(stored[i], 3.0f * float(i + 1)) << "element " << i;
  }
}

TEST_F(GlTest, RayGenerationMatchesCameraContract) {
  const int w = 7, h = 5;  // not square, odd sizes
  CameraSpec camera{{1.0f, 2.0f, 3.0f}, {0.5f, -1.0f, 0.25f}, {0.0f, 1.0f, 0.2f}, 52.0f};
  const CameraBasis basis = makeCameraBasis(camera, w, h);
  InOutStream rays(w, h, kRaySurfaceCount);
  StreamKernel raygen("raygen", "raygen.frag");
  setRaygenCamera(raygen, basis);
  rays.enable();
  rays.clearDepth(1.0f);
  rays.setWriteSurfaces({0, 1, 2, 3, 4, 5, 6});
  raygen.execute();
  const auto origin = rays.read(kOriginSurface), direction = rays.read(kDirectionSurface),
             state = rays.read(kStateSurface), hit = rays.read(kHitSurface);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const size_t i = size_t(py) * w + px;
      const Ray expected = primaryRay(basis, px, py);
      EXPECT_EQ(glm::vec3(origin[i]), expected.origin);
      EXPECT_EQ(origin[i].w, float(RayKind::Nearest));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(direction[i][k], expected.direction[k], 2e-7f) << px << "," << py;
      EXPECT_EQ(direction[i].w, kInfinity);
      EXPECT_EQ(state[i], glm::vec4(packIndex(0), 0.0f, 0.0f, 1.0f));
      EXPECT_EQ(hit[i].x, kInfinity);
    }
  // The contract's orientation: row 0 looks up, column 0 looks left.
  EXPECT_GT(glm::dot(glm::vec3(direction[0]), basis.up), 0.0f);
  EXPECT_LT(glm::dot(glm::vec3(direction[0]), basis.right), 0.0f);
}

// The compute stage (stream/stream_stage.h) runs a kernel's compute variant
// over the stream's active elements and writes what its fragment pass
// writes, bit for bit: here all seven surfaces of ray generation, on a
// stream whose sides are not multiples of the work group's tile, first over
// every element, then over those a cull left active; its stores go to one
// storage block, or through image units where a stream is larger than the
// driver's largest block (forced here).
TEST_F(GlTest, ComputeStageWritesWhatTheFragmentPassWrites) {
  const int w = 37, h = 23;
  const CameraBasis basis = makeCameraBasis(CameraSpec{{1.0f, 2.0f, 3.0f}, {0.5f, -1.0f, 0.25f}, {0, 1, 0}, 52.0f}, w, h);
  std::vector<glm::vec4> state(size_t(w * h));
  for (size_t i = 0; i < state.size(); ++i) state[i].w = (i * 7919) % 3 == 0 ? 0.0f : 1.0f;  // a third finished
  enum { kFragment, kComputeBlock, kComputeImages, kRuns };
  std::vector<std::vector<glm::vec4>> written[kRuns];
  uint64_t retired[kRuns] = {};
  std::vector<float> active[kRuns];
  for (int run = kFragment; run < kRuns; ++run) {
    const StreamStageScope scope(run == kFragment ? StreamStage::Fragment : StreamStage::Compute);
    InOutStream::limitStorageBlock(run == kComputeImages ? 1 : 0);
    InOutStream rays(w, h, kRaySurfaceCount), flags(w, h, 1);
    InOutStream::limitStorageBlock(0);
    EXPECT_EQ(rays.storesThroughImages(), run == kComputeImages);
    for (int s = 0; s < kRaySurfaceCount; ++s) rays.upload(s, std::vector<glm::vec4>(size_t(w * h), glm::vec4(-7.0f)));
    flags.upload(0, state);
    StreamKernel raygen("raygen", "raygen.frag");
    StreamKernel cull("cull", "cull.frag", StreamKernel::Depth::Cull);
    cull.bindInput("uState", flags, 0);
    setRaygenCamera(raygen, basis);
    rays.enable();
    rays.clearDepth(1.0f);
    rays.setWriteSurfaces({0, 1, 2, 3, 4, 5, 6});
    raygen.execute();
    for (int s = 0; s < kRaySurfaceCount; ++s) written[run].push_back(rays.read(s));
    retired[run] = cull.execute(true);
    active[run] = rays.readDepth();
    setRaygenCamera(raygen, makeCameraBasis(CameraSpec{{-1.0f, 0.0f, 0.0f}, {0, 0, 0}, {0, 1, 0}, 40.0f}, w, h));
    rays.setWriteSurfaces({InOutStream::kNoSurface, 1});  // only the directions: origins keep the first camera's
    raygen.execute();
    rays.disable();
    for (int s = 0; s < kRaySurfaceCount; ++s) written[run].push_back(rays.read(s));
  }
  for (int run : {kComputeBlock, kComputeImages}) {
    SCOPED_TRACE(run == kComputeBlock ? "stores to a storage block" : "stores through image units");
    for (size_t s = 0; s < written[0].size(); ++s)
      for (size_t i = 0; i < size_t(w * h); ++i)
        ASSERT_EQ(written[run][s][i], written[0][s][i]) << "surface " << s % kRaySurfaceCount << ", element " << i;
    EXPECT_EQ(retired[run], retired[0]);
    EXPECT_EQ(active[run], active[0]);
  }
  EXPECT_EQ(written[1][kOriginSurface].back(), glm::vec4(basis.eye, float(RayKind::Nearest)));  // the last one ran
  EXPECT_EQ(retired[1], uint64_t(std::count_if(state.begin(), state.end(), [](const glm::vec4& e) { return e.w == 0; })));
  // Elements the cull retired kept the first camera's directions; the others took the second's.
  const size_t finished = 0, live = 1;
  ASSERT_EQ(state[finished].w, 0.0f);
  ASSERT_NE(state[live].w, 0.0f);
  EXPECT_EQ(written[1][kRaySurfaceCount + kDirectionSurface][finished], written[1][kDirectionSurface][finished]);
  EXPECT_NE(written[1][kRaySurfaceCount + kDirectionSurface][live], written[1][kDirectionSurface][live]);
}

// The compute stage's active set follows the depth buffer's rules: a cull
// of the active elements counts what it retires and keeps the rest active;
// the row limit bounds what runs; saveDepth/restoreDepth bring a set back.
TEST_F(GlTest, ComputeStageKeepsTheActiveSetAsTheDepthBufferDoes) {
  const int w = 19, h = 11;
  std::vector<glm::vec4> state(size_t(w * h), glm::vec4(1.0f));
  for (size_t i = 0; i < state.size(); i += 4) state[i].w = 0.0f;
  std::vector<float> seen[2][4];
  uint64_t counts[2][4] = {};
  for (const auto stage : {StreamStage::Fragment, StreamStage::Compute}) {
    const StreamStageScope scope(stage);
    InOutStream flags(w, h, 1);
    StreamKernel cull("cull", "cull.frag", StreamKernel::Depth::Cull);
    cull.bindInput("uState", flags, 0);
    flags.upload(0, state);
    flags.enable();
    flags.clearDepth(1.0f);
    counts[int(stage)][0] = cull.execute(true);  // every fourth element retires
    seen[int(stage)][0] = flags.readDepth();
    flags.saveDepth();
    counts[int(stage)][1] = cull.execute(true);  // nothing more to retire
    for (size_t i = 1; i < state.size(); i += 4) state[i].w = 0.0f;
    flags.upload(0, state);
    flags.setRowLimit(5);
    flags.enable();  // the limit applies from the next enable()
    counts[int(stage)][2] = cull.execute(true);  // every fourth + 1, in the first five rows
    seen[int(stage)][1] = flags.readDepth();
    flags.restoreDepth();
    seen[int(stage)][2] = flags.readDepth();
    flags.setRowLimit(0);
    flags.enable();
    flags.clearDepth(0.0f);
    counts[int(stage)][3] = cull.execute(true);  // nothing is active
    seen[int(stage)][3] = flags.readDepth();
    flags.disable();
    for (size_t i = 1; i < state.size(); i += 4) state[i].w = 1.0f;
  }
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(counts[1][k], counts[0][k]) << "count " << k;
    EXPECT_EQ(seen[1][k], seen[0][k]) << "depth " << k;
  }
  EXPECT_EQ(counts[1][0], uint64_t((w * h + 3) / 4));
  EXPECT_EQ(counts[1][1], 0u);
  EXPECT_EQ(counts[1][2], uint64_t((5 * w - 1 + 3) / 4));
  EXPECT_EQ(counts[1][3], 0u);
}

// A kernel runs only on streams of its own stage: the mix is a one-line error.
TEST_F(GlTest, AKernelRefusesAStreamOfTheOtherStage) {
  InOutStream compute(4, 4, 1, StreamStage::Compute), fragment(4, 4, 1, StreamStage::Fragment);
  StreamKernel onFragment("raygen", "raygen.frag", StreamStage::Fragment);
  StreamKernel onCompute("raygen", "raygen.frag", StreamStage::Compute);
  compute.enable();
  EXPECT_THROW(onFragment.execute(), GlError);
  fragment.enable();
  EXPECT_THROW(onCompute.execute(), GlError);
  fragment.disable();
}

// Runs test_functions.frag with `define` over elements given as up to 5 input surfaces.
std::vector<glm::vec4> runFunctionKernel(const char* define, const std::vector<std::vector<glm::vec4>>& inputs,
                                         StreamKernel::Stage stage = StreamKernel::Stage::Fragment) {
  const int n = int(inputs[0].size());
  InOutStream in(n, 1, 5, stage), out(n, 1, 1, stage);
  StreamKernel kernel("test", "test_functions.frag", stage, {define});
  const char* names[] = {"uIn0", "uIn1", "uIn2", "uIn3", "uIn4"};
  for (size_t s = 0; s < inputs.size(); ++s) {
    in.upload(int(s), inputs[s]);
    kernel.bindInput(names[s], in, int(s));
  }
  if (stage == StreamKernel::Stage::Compute) {
    kernel.bindOutput(0, out, 0);
    kernel.dispatch(n, 1);
    return out.read(0);
  }
  out.enable();
  out.clearDepth(1.0f);
  out.setWriteSurfaces({0});
  kernel.execute();
  out.disable();
  return out.read(0);
}

TEST_F(GlTest, SlabTestMatchesCpp) {
  const Aabb box{{-1.0f, -1.0f, -1.0f}, {1.0f, 2.0f, 1.0f}};
  std::vector<Ray> rays = {
      {{-5, 0, 0}, {1, 0, 0}},         // straight through
      {{-5, 3, 0}, {1, 0, 0}},         // parallel, above
      {{-5, 2, 0}, {1, 0, 0}},         // parallel, grazing the top face
      {{0, 0, 0}, {0, 0, 1}},          // from inside
      {{0, 0, 5}, {0, 0, 1}},          // box behind the origin
      {{-5, -5, -5}, {1, 1, 1}},       // diagonal
      {{-1, -1, -1}, {0, 1, 0}},       // along an edge
      {{-5, 0, 0}, {1, 0, 0}, 3.0f},   // tBest before the box
      {{-5, 0, 0}, {1, 0, 0}, 4.5f},   // tBest inside the box
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  for (int i = 0; i < 200; ++i)
    rays.push_back({{u(rng), u(rng), u(rng)}, glm::normalize(glm::vec3(u(rng), u(rng), u(rng))), std::abs(u(rng)) * 2});
  std::vector<glm::vec4> o, d, lo, hi;
  for (const Ray& r : rays) {
    o.emplace_back(r.origin, 0.0f);
    d.emplace_back(r.direction, 0.0f);
    lo.emplace_back(box.min, 0.0f);
    hi.emplace_back(box.max, r.tMax);
  }
  const auto result = runFunctionKernel("TEST_SLAB", {o, d, lo, hi});
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool expected = intersectsBox(rays[i].origin, safeInverse(rays[i].direction), box, rays[i].tMax);
    EXPECT_EQ(result[i].x != 0.0f, expected) << "ray " << i;
    hits += expected;
  }
  EXPECT_GT(hits, 20);  // the random rays exercise both outcomes
  EXPECT_LT(hits, int(rays.size()) - 20);
  // Its compute variant reads the same samplers and answers alike.
  EXPECT_EQ(runFunctionKernel("TEST_SLAB", {o, d, lo, hi}, StreamKernel::Stage::Compute), result);
}

TEST_F(GlTest, TriangleTestMatchesCpp) {
  const Triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Triangle degenerate{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  struct Case {
    Ray ray;
    Triangle tri;
  };
  std::vector<Case> cases = {
      {{{0.25f, 0.25f, 1}, {0, 0, -1}}, tri},           // front face
      {{{0.25f, 0.25f, -1}, {0, 0, 1}}, tri},           // back face (two-sided)
      {{{0.5f, 0.5f, 1}, {0, 0, -1}}, tri},             // on the hypotenuse
      {{{0, 0, 1}, {0, 0, -1}}, tri},                   // through a vertex
      {{{2, 2, 1}, {0, 0, -1}}, tri},                   // miss
      {{{0.25f, 0.25f, 1}, {1, 0, 0}}, tri},            // parallel to the plane
      {{{0.25f, 0.25f, 1}, {0, 0, -1}, 0.5f}, tri},     // beyond tBest
      {{{0.25f, 0.25f, -1}, {0, 0, -1}}, tri},          // behind the origin
      {{{0.5f, 0.5f, 3}, {0, 0, -1}}, degenerate},      // zero area
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (int i = 0; i < 300; ++i) {
    const Triangle t{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    const glm::vec3 origin(u(rng), u(rng), u(rng) + 4.0f);
    cases.push_back({{origin, glm::normalize(t.centroid() + 0.3f * glm::vec3(u(rng), u(rng), 0) - origin)}, t});
  }
  std::vector<glm::vec4> o, d, a, b, c;
  for (size_t i = 0; i < cases.size(); ++i) {
    o.emplace_back(cases[i].ray.origin, 0.0f);
    d.emplace_back(cases[i].ray.direction, cases[i].ray.tMax);
    a.emplace_back(cases[i].tri.v0, 0.0f);
    b.emplace_back(cases[i].tri.v1, 0.0f);
    c.emplace_back(cases[i].tri.v2, packIndex(uint32_t(i)));
  }
  const auto result = runFunctionKernel("TEST_TRIANGLE", {o, d, a, b, c});
  int found = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    Hit expected{cases[i].ray.tMax};
    const bool hit = intersectTriangle(cases[i].ray.origin, cases[i].ray.direction, cases[i].tri, uint32_t(i), expected);
    const bool gpuHit = result[i].w >= 0.0f;
    EXPECT_EQ(gpuHit, hit) << "case " << i;
    if (hit && gpuHit) {
      found++;
      EXPECT_EQ(unpackIndex(result[i].w), uint32_t(i));
      EXPECT_NEAR(result[i].x, expected.t, 1e-5f * std::max(1.0f, expected.t)) << "case " << i;
      EXPECT_NEAR(result[i].y, expected.u, 1e-5f) << "case " << i;
      EXPECT_NEAR(result[i].z, expected.v, 1e-5f) << "case " << i;
    }
  }
  EXPECT_GT(found, 50);
}

// A small BVH and a handful of rays through it.
struct BvhFixture {
  std::vector<Triangle> tris = testmesh::uvSphere(8, 12);
  Bvh bvh = buildKayKajiya(tris);
  EscapeSequence sequence = flattenEscapeSequence(bvh, tris);
  std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 16, 3);
};

TEST_F(GlTest, OneTraversalPassStopsAtTheLoopLimit) {
  BvhFixture f;
  const int loopLimit = 3;
  GpuBvhTraversal traversal(f.sequence, AccelStats{}, GpuTraversalConfig{{}, loopLimit});
  // Stop after one pass by retiring nothing and reporting all done.
  std::vector<glm::vec4> state;
  {
    InOutStream stream(int(f.rays.size()), 1, kRaySurfaceCount);
    std::vector<glm::vec4> o, d, s, h;
    for (const Ray& r : f.rays) {
      o.emplace_back(r.origin, float(RayKind::Nearest));
      d.emplace_back(r.direction, r.tMax);
      s.emplace_back(packIndex(0), 0.0f, 0.0f, 1.0f);
      h.emplace_back(r.tMax, 0.0f, 0.0f, packIndex(0));
    }
    stream.upload(kOriginSurface, o);
    stream.upload(kDirectionSurface, d);
    stream.upload(kStateSurface, s);
    stream.upload(kHitSurface, h);
    stream.enable();
    stream.clearDepth(1.0f);
    EXPECT_EQ(traversal.trace(stream, f.rays.size(), [&] { return uint64_t(f.rays.size()); }), 1u);
    state = stream.read(kStateSurface);
  }
  for (size_t i = 0; i < f.rays.size(); ++i) {
    EscapeCursor cursor;
    cursor.best.t = f.rays[i].tMax;
    const bool unfinished = stepEscapeSequence(f.sequence, f.rays[i], false, cursor, loopLimit);
    EXPECT_EQ(unpackIndex(state[i].x), cursor.index) << "ray " << i;
    EXPECT_EQ(state[i].y, float(cursor.stats.steps));
    EXPECT_EQ(state[i].z, float(cursor.stats.triangleTests));
    EXPECT_EQ(state[i].w, unfinished ? 1.0f : 0.0f);
  }
}

TEST_F(GlTest, TraversalResumesAcrossPassesWithTheSameResult) {
  BvhFixture f;
  std::vector<test::TracedRays> results;
  for (int loopLimit : {1, 2, 7, 100000}) {
    GpuBvhTraversal traversal(f.sequence, AccelStats{}, GpuTraversalConfig{{}, loopLimit});
    results.push_back(test::traceOnGpu(traversal, f.rays));
  }
  EXPECT_GT(results[0].passes, results[3].passes);
  EXPECT_EQ(results[3].passes, 1u);
  for (size_t i = 0; i < f.rays.size(); ++i) {
    RayStats stats;
    const Hit cpu = traverseEscapeSequence(f.sequence, f.rays[i], false, &stats);
    for (const auto& r : results) {
      EXPECT_EQ(r.hits[i].id, cpu.id) << "ray " << i;
      EXPECT_EQ(r.hits[i].t, results[0].hits[i].t) << "ray " << i;  // bit-identical for every loop limit
      EXPECT_EQ(r.state[i].y, float(stats.steps)) << "ray " << i;
      EXPECT_EQ(r.state[i].z, float(stats.triangleTests)) << "ray " << i;
    }
  }
}

TEST_F(GlTest, CullRetiresFinishedElementsAndQueriesCountThem) {
  const int w = 16, h = 8;
  InOutStream stream(w, h, kRaySurfaceCount);
  std::vector<glm::vec4> state(w * h);
  uint64_t finished = 0;
  for (int i = 0; i < w * h; ++i) {
    const bool done = (i % 3 == 0) || (i / w == 5);
    state[i] = glm::vec4(packIndex(uint32_t(i)), float(i), 0.0f, done ? 0.0f : 1.0f);
    finished += done;
  }
  stream.upload(kStateSurface, state);
  StreamKernel cull("cull", "cull.frag", StreamKernel::Depth::Cull);
  cull.bindInput("uState", stream, kStateSurface);
  stream.enable();
  stream.clearDepth(1.0f);
  EXPECT_EQ(cull.execute(true), finished);
  EXPECT_EQ(cull.execute(true), 0u);  // already retired elements are not counted again
  const std::vector<float> depth = stream.readDepth();
  for (int i = 0; i < w * h; ++i) EXPECT_EQ(depth[i], state[i].w == 0.0f ? 0.0f : 1.0f) << "element " << i;
  EXPECT_EQ(stream.read(kStateSurface), state);  // the cull writes no colour

  // A compute kernel now runs only on the active elements: the query counts
  // them, and retired elements keep their surfaces untouched.
  StreamKernel raygen("raygen", "raygen.frag");
  raygen.set("uResolution", glm::vec2(w, h));
  stream.setWriteSurfaces({0, 1, 2, 3, 4, 5, 6});
  EXPECT_EQ(raygen.execute(true), uint64_t(w * h) - finished);
  const std::vector<glm::vec4> after = stream.read(kStateSurface);
  for (int i = 0; i < w * h; ++i)
    EXPECT_EQ(after[i], state[i].w == 0.0f ? state[i] : glm::vec4(packIndex(0), 0, 0, 1)) << "element " << i;
}

// Two facing triangles, one diffuse and one mirror, and a light.
Scene shadingScene() {
  Scene s;
  s.name = "shading";
  s.triangles = {{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{-1, -1, 2}, {0, 1, 2}, {1, -1, 2}}};
  s.vertexNormals = {{glm::normalize(glm::vec3(0.2f, 0, 1)), glm::vec3(0, 0, 1), glm::normalize(glm::vec3(0, 0.3f, 1))},
                     {glm::vec3(0, 0, -1), glm::vec3(0, 0, -1), glm::vec3(0, 0, -1)}};
  s.materials = {Material{{0.8f, 0.5f, 0.25f}, {0, 0, 0}}, Material{{0.1f, 0.1f, 0.1f}, {0.9f, 0.8f, 0.7f}}};
  s.materialIds = {0, 1};
  s.light = {{0.3f, 0.2f, 1.5f}, {1.0f, 0.9f, 0.8f}};
  s.background = {0.1f, 0.2f, 0.3f};
  s.ambient = 0.15f;
  return s;
}

TEST_F(GlTest, ShadingMatchesCpp) {
  const Scene scene = shadingScene();
  const float epsilon = secondaryRayEpsilon(scene);
  // Elements: each kind of ray with each outcome, shaded as a middle and as the last bounce.
  struct Element {
    PathState path;
    Hit hit;
  };
  std::vector<Element> elements;
  auto nearest = [](glm::vec3 o, glm::vec3 d) {
    PathState p;
    p.ray = Ray{o, glm::normalize(d), kInfinity};
    p.kind = RayKind::Nearest;
    p.throughput = glm::vec3(0.9f, 0.7f, 0.5f);
    p.color = glm::vec3(0.01f, 0.02f, 0.03f);
    return p;
  };
  const glm::vec3 eye(0.1f, -0.2f, 1.0f);
  for (glm::vec3 target : {glm::vec3(0.1f, -0.3f, 0.0f), glm::vec3(-0.2f, 0.1f, 0.0f)}) {
    PathState p = nearest(eye, target - eye);
    Hit hit;
    ASSERT_TRUE(intersectTriangle(p.ray.origin, p.ray.direction, scene.triangles[0], 0, hit));
    elements.push_back({p, hit});                                    // diffuse hit
  }
  {
    PathState p = nearest(eye, glm::vec3(0.0f, -0.2f, 2.0f) - eye);
    Hit hit;
    ASSERT_TRUE(intersectTriangle(p.ray.origin, p.ray.direction, scene.triangles[1], 1, hit));
    elements.push_back({p, hit});                                    // mirror hit
  }
  elements.push_back({nearest(eye, {1, 0, 0}), Hit{}});              // miss
  PathState shadow;
  shadow.kind = RayKind::Shadow;
  shadow.ray = Ray{{0, 0, 0.01f}, glm::normalize(glm::vec3(0.3f, 0.2f, 1.5f)), 1.5f};
  shadow.pending = glm::vec3(0.3f, 0.2f, 0.1f);
  elements.push_back({shadow, Hit{}});                               // shadow ray reaches the light
  elements.push_back({shadow, Hit{0.7f, 0.1f, 0.1f, 1}});            // shadow ray occluded
  PathState none;
  none.kind = RayKind::None;
  none.color = glm::vec3(0.5f);
  elements.push_back({none, Hit{}});                                 // finished element

  for (int last = 0; last <= 1; ++last) {
    const int n = int(elements.size());
    InOutStream stream(n, 1, kRaySurfaceCount);
    // The seven surfaces shading reads and writes (the aux surface is traversal-only).
    const int shadedSurfaces = kAuxSurface;
    std::vector<std::vector<glm::vec4>> surfaces(shadedSurfaces);
    for (const Element& e : elements) {
      surfaces[kOriginSurface].emplace_back(e.path.ray.origin, float(e.path.kind));
      surfaces[kDirectionSurface].emplace_back(e.path.ray.direction, e.path.ray.tMax);
      surfaces[kStateSurface].emplace_back(packIndex(99), 5.0f, 3.0f, 0.0f);
      surfaces[kHitSurface].emplace_back(e.hit.found() ? e.hit.t : e.path.ray.tMax, e.hit.u, e.hit.v,
                                         packIndex(e.hit.found() ? e.hit.id : 0));
      surfaces[kColorSurface].emplace_back(e.path.color, 0.0f);
      surfaces[kThroughputSurface].emplace_back(e.path.throughput, 10.0f);
      surfaces[kPendingSurface].emplace_back(e.path.pending, 20.0f);
    }
    for (int s = 0; s < shadedSurfaces; ++s) stream.upload(s, surfaces[s]);
    ConstInputStream triangles(triangleShadingTexels(scene), "triangles"), materials(materialTexels(scene), "materials");
    StreamKernel shade("shade", "shade.frag", StreamKernel::Depth::Test,
                       {streamPagesDefine({&triangles, &materials}), shadingTexelsDefine(scene)});
    const char* samplers[] = {"uOrigin", "uDirection", "uState", "uHit", "uColor", "uThroughput", "uPending"};
    for (int s = 0; s < shadedSurfaces; ++s) shade.bindInput(samplers[s], stream, s);
    shade.bindInput("uTriangles", triangles);
    shade.bindInput("uMaterials", materials);
    shade.set("uLightPosition", scene.light.position);
    shade.set("uLightColor", scene.light.color);
    shade.set("uBackground", scene.background);
    shade.set("uAmbient", scene.ambient);
    shade.set("uEpsilon", epsilon);
    shade.set("uLastBounce", last);
    stream.enable();
    stream.clearDepth(1.0f);
    stream.setWriteSurfaces({0, 1, 2, 3, 4, 5, 6});
    shade.execute();
    std::vector<std::vector<glm::vec4>> out;
    for (int s = 0; s < shadedSurfaces; ++s) out.push_back(stream.read(s));

    for (int i = 0; i < n; ++i) {
      PathState expected = elements[i].path;
      shadeElement(scene, epsilon, last != 0, elements[i].hit, expected);
      SCOPED_TRACE("element " + std::to_string(i) + (last ? " (last bounce)" : ""));
      EXPECT_EQ(out[kOriginSurface][i].w, float(expected.kind));
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(out[kColorSurface][i][k], expected.color[k], 1e-5f);
        EXPECT_NEAR(out[kThroughputSurface][i][k], expected.throughput[k], 1e-6f);
        if (expected.kind != RayKind::None) {
          EXPECT_NEAR(out[kOriginSurface][i][k], expected.ray.origin[k], 1e-5f);
          EXPECT_NEAR(out[kDirectionSurface][i][k], expected.ray.direction[k], 1e-5f);
        }
        if (expected.kind == RayKind::Shadow) {
          EXPECT_NEAR(out[kPendingSurface][i][k], expected.pending[k], 1e-5f);
        }
      }
      if (expected.kind == RayKind::Shadow) {
        EXPECT_NEAR(out[kDirectionSurface][i].w, expected.ray.tMax, 1e-5f * expected.ray.tMax);
      } else if (expected.kind == RayKind::Nearest) {
        EXPECT_EQ(out[kDirectionSurface][i].w, kInfinity);
      }
      EXPECT_EQ(out[kStateSurface][i], glm::vec4(packIndex(0), 0, 0, expected.kind != RayKind::None ? 1.0f : 0.0f));
      // The traversal counters of the ray just traced are added to the totals.
      EXPECT_EQ(out[kThroughputSurface][i].w, 15.0f);
      EXPECT_EQ(out[kPendingSurface][i].w, 23.0f);
    }
    // The cases cover every branch: a shadow ray, a reflection and a finished element.
    if (!last) {
      EXPECT_EQ(out[kOriginSurface][0].w, float(RayKind::Shadow));
      EXPECT_EQ(out[kOriginSurface][2].w, float(RayKind::Nearest));
    }
  }
}

TEST_F(GlTest, CompileErrorsNameKernelFileAndLine) {
  // A define that breaks the sampler declaration on line 6 of cull.frag.
  try {
    StreamKernel broken("broken_cull", "cull.frag", StreamKernel::Depth::Cull, {"uState 1.0 +"});
    FAIL() << "expected a compile error";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken_cull"), std::string::npos) << message;
    EXPECT_NE(message.find("cull.frag:6"), std::string::npos) << message;
  }
  EXPECT_THROW(StreamKernel("missing", "no_such_kernel.frag"), GlError);
}

TEST_F(GlTest, StreamSizeOutsideTheGlLimitIsAnError) {
  EXPECT_THROW(InOutStream(0, 4, 1), GlError);
  EXPECT_THROW(InOutStream(test::glContext().maxTextureSize() + 1, 1, 1), GlError);
  EXPECT_THROW(InOutStream(4, 4, 9), GlError);
}

// Past the block size a kernel can address (llvmpipe: 2 GiB, more than the
// 128 MiB it reports) a buffer is refused with the data's name, before any
// allocation, instead of crashing the first pass that binds it.
TEST_F(GlTest, StorageBufferPastTheBlockLimitIsAnError) {
  StorageBuffer buffer("huge stacks");
  try {
    buffer.reserve((uint64_t(1) << 40) / sizeof(float));
    FAIL() << "a 1 TiB storage buffer was accepted";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("huge stacks: 1048576 MiB exceed"), std::string::npos) << e.what();
  }
  EXPECT_EQ(buffer.floats(), 0u);
  buffer.reserve(1024);  // still usable
  EXPECT_EQ(buffer.floats(), 1024u);
}

}  // namespace
}  // namespace passtrace
