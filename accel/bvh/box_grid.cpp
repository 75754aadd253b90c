#include "accel/bvh/box_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

namespace passtrace {
namespace {

constexpr uint32_t kPlaneBits = 15;
constexpr double kMarginSteps = 1.0 / 256.0;

// Bit 30 the complement of bit 29: the exponent (bits 23-30) is 64-191, never
// 0 or 255, so the float is normal; sign 0.
float tagged(uint32_t payload) { return std::bit_cast<float>(payload | ((~payload >> 29) & 1u) << 30); }

std::string describe(const Aabb& box) {
  const auto v = [](glm::vec3 p) {
    return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
  };
  return v(box.min) + " - " + v(box.max);
}

}  // namespace

BoxGrid BoxGrid::over(const Aabb& bounds) {
  BoxGrid grid;
  // No axis finer than 2^-20 of the widest: a flat axis's grid units would
  // otherwise map ray origins a scene away to float overflow.
  const glm::vec3 extents = bounds.max - bounds.min;
  const float widest = std::max(std::max(extents.x, extents.y), extents.z);
  for (int a = 0; a < 3; ++a) {
    const float extent = bounds.max[a] - bounds.min[a];
    if (!std::isfinite(bounds.min[a]) || !std::isfinite(bounds.max[a]) || !(extent >= 0.0f) || !std::isfinite(extent))
      throw std::invalid_argument("box grid: bounds " + describe(bounds) + " are not a finite box of float range");
    // From the power of two just below extent / kMaxPlane upwards: the loop runs a step or two, more where
    // the bounds are small against their distance from zero (the origin must round below them).
    const float finest = std::max(extent / float(kMaxPlane), widest * 0x1p-20f);
    const int exponent = finest > 0.0f ? std::ilogb(finest) : -100;
    for (float step = std::ldexp(1.0f, std::max(exponent, -100));; step *= 2.0f) {
      if (step >= 0x1p100f)
        throw std::invalid_argument("box grid: bounds " + describe(bounds) + " are too large for float planes");
      grid.step[a] = step;
      grid.invStep[a] = 1.0f / step;
      grid.origin[a] = bounds.min[a] - step;
      const double margin = kMarginSteps * step;
      if (double(bounds.min[a]) - grid.plane(a, 0) >= margin && grid.plane(a, kMaxPlane) - double(bounds.max[a]) >= margin)
        break;
    }
  }
  return grid;
}

glm::vec3 BoxGrid::encode(const Aabb& box) const {
  glm::vec3 texel;
  for (int a = 0; a < 3; ++a) {
    const double margin = kMarginSteps * step[a];
    const double lowest = double(box.min[a]) - margin, highest = double(box.max[a]) + margin;
    if (!(plane(a, 0) <= lowest && plane(a, kMaxPlane) >= highest))
      throw std::invalid_argument("box grid: box " + describe(box) + " lies outside the grid");
    // The innermost planes at least the margin outside the box (exact in double).
    const auto clamped = [](double q) { return uint32_t(std::clamp(q, 0.0, double(kMaxPlane))); };
    uint32_t lo = clamped(std::floor((lowest - double(origin[a])) / double(step[a])));
    while (lo > 0 && plane(a, lo) > lowest) --lo;
    while (lo < kMaxPlane && plane(a, lo + 1) <= lowest) ++lo;
    uint32_t hi = clamped(std::ceil((highest - double(origin[a])) / double(step[a])));
    while (hi < kMaxPlane && plane(a, hi) < highest) ++hi;
    while (hi > lo && plane(a, hi - 1) >= highest) --hi;
    texel[a] = tagged(lo << kPlaneBits | hi);
  }
  return texel;
}

Aabb BoxGrid::gridPlanes(const glm::vec3& xyz) {
  const glm::uvec3 bits{std::bit_cast<uint32_t>(xyz.x), std::bit_cast<uint32_t>(xyz.y), std::bit_cast<uint32_t>(xyz.z)};
  return {glm::vec3((bits >> kPlaneBits) & kMaxPlane), glm::vec3(bits & kMaxPlane)};
}

}  // namespace passtrace
