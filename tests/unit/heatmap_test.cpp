#include <gtest/gtest.h>

#include "render/heatmap.h"

namespace passtrace {
namespace {

TEST(Heatmap, RampRunsFromDarkBlueToRedAndScalesToTheMaximum) {
  const std::vector<float> rgb = heatmapRgb({0.0f, 50.0f, 100.0f, 250.0f}, 250.0f);
  ASSERT_EQ(rgb.size(), 12u);
  // 0 is the dark end, the maximum (250) the red end.
  EXPECT_LT(rgb[0] + rgb[1] + rgb[2], 0.3f);
  EXPECT_GT(rgb[9], 0.8f);
  EXPECT_LT(rgb[10], 0.2f);
  // Monotone in "heat": more steps are never darker in red.
  EXPECT_LE(rgb[3], rgb[6]);
  // An explicit maximum clamps larger values to the red end.
  const std::vector<float> clamped = heatmapRgb({1000.0f}, 100.0f);
  EXPECT_FLOAT_EQ(clamped[0], rgb[9]);
  EXPECT_FLOAT_EQ(clamped[2], rgb[11]);
  // By default the 99th percentile is the top: one outlier among many does not set the scale.
  std::vector<float> many(200, 10.0f);
  many.push_back(1e6f);
  const std::vector<float> scaled = heatmapRgb(many);
  EXPECT_FLOAT_EQ(scaled[0], rgb[9]);  // 10 is at the red end
  // All zeros stay at the dark end instead of dividing by zero.
  const std::vector<float> zeros = heatmapRgb({0.0f, 0.0f});
  EXPECT_FLOAT_EQ(zeros[0], rgb[0]);
}

}  // namespace
}  // namespace passtrace
