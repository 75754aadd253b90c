#pragma once
// Heat maps of per-pixel traversal cost (seed 000, figure 1): values mapped
// through a perceptual colour ramp from dark blue (none) to red (the maximum).

#include <vector>

namespace passtrace {

// RGB image (3 floats per value) with `values` scaled so that `maxValue`
// (or, when it is 0, the 99th percentile of the values) is the top of the
// ramp; larger values stay at the top.
std::vector<float> heatmapRgb(const std::vector<float>& values, float maxValue = 0.0f);

}  // namespace passtrace
