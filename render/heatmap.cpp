#include "render/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace passtrace {

std::vector<float> heatmapRgb(const std::vector<float>& values, float maxValue) {
  // Stops of a blue-cyan-green-yellow-red ramp, evenly spaced.
  static constexpr std::array<std::array<float, 3>, 6> kRamp{{{0.02f, 0.02f, 0.15f},
                                                              {0.10f, 0.25f, 0.80f},
                                                              {0.10f, 0.75f, 0.85f},
                                                              {0.30f, 0.85f, 0.25f},
                                                              {0.98f, 0.85f, 0.15f},
                                                              {0.85f, 0.10f, 0.05f}}};
  if (maxValue <= 0.0f && !values.empty()) {
    // The 99th percentile: a few pathological pixels should not wash out the rest.
    std::vector<float> sorted = values;
    const size_t k = std::min(sorted.size() - 1, size_t(0.99 * double(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    maxValue = sorted[k];
  }
  std::vector<float> rgb;
  rgb.reserve(3 * values.size());
  for (float v : values) {
    const float x = maxValue > 0.0f ? std::clamp(v / maxValue, 0.0f, 1.0f) * float(kRamp.size() - 1) : 0.0f;
    const size_t i = std::min(size_t(x), kRamp.size() - 2);
    const float f = x - float(i);
    for (int c = 0; c < 3; ++c) rgb.push_back(kRamp[i][c] + f * (kRamp[i + 1][c] - kRamp[i][c]));
  }
  return rgb;
}

}  // namespace passtrace
