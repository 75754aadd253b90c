#include "accel/kd/kd_termination.h"

#include <cmath>

namespace passtrace {

int kdPapayMaxDepth(size_t triangleCount) {
  if (triangleCount <= 1) return 2;
  return static_cast<int>(std::ceil(2.0 + 1.2 * std::log2(static_cast<double>(triangleCount))));
}

size_t kdPapayLeafBelow(size_t triangleCount) {
  if (triangleCount < 700'000) return 2;
  return triangleCount <= 3'000'000 ? 8 : 12;
}

KdBuildConfig kdWithTermination(KdBuildConfig config, KdTermination rule, size_t triangleCount) {
  if (rule == KdTermination::Papay) {
    config.maxDepth = kdPapayMaxDepth(triangleCount);
    config.minElements = static_cast<int>(kdPapayLeafBelow(triangleCount)) - 1;
  }
  return config;
}

}  // namespace passtrace
