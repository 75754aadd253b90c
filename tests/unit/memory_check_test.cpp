// The memory check's estimate (render/memory_check.h) counts what the GPU
// renderer keeps per pixel beyond its ray stream: the Whitted ray stacks and
// the compaction's second stream (GpuRenderer::extraBytesPerPixel).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "render/gpu_renderer.h"
#include "render/memory_check.h"

namespace passtrace {
namespace {

TEST(MemoryCheck, GpuRendererCountsItsWhittedStacksAndCompactionStream) {
  ShadingConfig thesis, whitted;
  whitted.mode = ShadingMode::Whitted;
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(thesis, Compaction::Off), 0.0);
  // 16 entries of 12 floats.
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(whitted, Compaction::Off), 768.0);
  // 8 RGBA32F surfaces, depth, two indices.
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(thesis, Compaction::On), 140.0);
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(whitted, Compaction::Always), 908.0);
}

// The compute stage keeps two 4-byte index lists per stream element: the rays'
// stream's, and the compaction stream's when compaction is on.
TEST(MemoryCheck, TheComputeStageCountsItsActiveElementLists) {
  ShadingConfig thesis;
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(thesis, Compaction::Off, StreamStage::Compute), 8.0);
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(thesis, Compaction::On, StreamStage::Compute), 140.0 + 16.0);
  EXPECT_EQ(GpuRenderer::extraBytesPerPixel(thesis, Compaction::Off, StreamStage::Fragment), 0.0);
}

TEST(MemoryCheck, ExtraBytesPerPixelGrowTheEstimateWithItsMargin) {
  const Structure& kk = *findStructure("kk-bvh");
  const uint64_t pixels = 1920 * 1080;
  const uint64_t base = estimatedRunBytes(RendererId::Gpu, &kk, 100000, pixels);
  const uint64_t whitted = estimatedRunBytes(RendererId::Gpu, &kk, 100000, pixels, 768.0);
  EXPECT_NEAR(double(whitted - base), 1.25 * 768.0 * double(pixels), 2.0);
}

// A model's bytes per triangle hold up to the size it was measured at and grow
// above it as its growth says: kd-trees' references outgrow their triangles.
TEST(MemoryCheck, ModelsGrowAsMeasuredAboveTheirSize) {
  const MemoryCost linear{300, 1.0}, growing{300, 1.1};
  for (uint64_t n : {uint64_t(1000), uint64_t(1000000), uint64_t(kMemoryModelTriangles)}) {
    EXPECT_DOUBLE_EQ(linear.bytesFor(n), 300.0 * double(n));
    EXPECT_DOUBLE_EQ(growing.bytesFor(n), 300.0 * double(n));
  }
  const double n = 25 * kMemoryModelTriangles;
  EXPECT_DOUBLE_EQ(linear.bytesFor(uint64_t(n)), 300.0 * n);
  EXPECT_NEAR(growing.bytesFor(uint64_t(n)), 300.0 * n * std::pow(25.0, 0.1), 1.0);
  // The check's estimate follows the row's model, with its margin.
  const Structure& pbrt = *findStructure("kd-pbrt");
  const uint64_t half = 50000000, full = 100000000;
  EXPECT_NEAR(double(estimatedRunBytes(RendererId::Cpu, &pbrt, full, 0) - estimatedRunBytes(RendererId::Cpu, &pbrt, half, 0)),
              1.25 * (pbrt.memory.cpu.bytesFor(full) - pbrt.memory.cpu.bytesFor(half)), 2.0);
}

// The second check runs with the scene loaded, so it adds what the process
// holds to what is available: residentBytes must see memory this process touches.
TEST(MemoryCheck, ResidentBytesSeeWhatThisProcessTouches) {
  const uint64_t before = residentBytes();
  ASSERT_GT(before, 0u);
  constexpr size_t kBytes = 256u << 20;
  std::vector<char> block(kBytes, 1);  // value-initialised: every page written
  const uint64_t after = residentBytes();
  EXPECT_GE(after, before + kBytes * 9 / 10) << before << " -> " << after;
  EXPECT_EQ(block[kBytes - 1], 1);
}

}  // namespace
}  // namespace passtrace
