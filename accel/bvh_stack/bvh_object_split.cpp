#include "accel/bvh_stack/bvh_object_split.h"

#include <algorithm>

namespace passtrace {
namespace {

uint32_t binOf(const BvhBuildRef& r, int axis, const Aabb& centroids, uint32_t bins) {
  const float extent = centroids.max[axis] - centroids.min[axis];
  const float c = r.box.center()[axis];
  const float at = (c - centroids.min[axis]) * (float(bins) / extent);
  return std::min(bins - 1, uint32_t(std::max(0.0f, at)));
}

}  // namespace

BvhObjectSplit findObjectSplit(std::span<const BvhBuildRef> refs, const Aabb& box, const BvhStackConfig& config) {
  BvhObjectSplit best;
  best.centroids = bvhCentroidBox(refs);
  const uint32_t bins = std::max(2u, config.bins);
  const float area = box.surfaceArea();
  std::vector<Aabb> binBox(bins), rightBox(bins);
  std::vector<uint32_t> binCount(bins);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(best.centroids.max[axis] > best.centroids.min[axis])) continue;
    std::fill(binBox.begin(), binBox.end(), Aabb{});
    std::fill(binCount.begin(), binCount.end(), 0u);
    for (const BvhBuildRef& r : refs) {
      const uint32_t b = binOf(r, axis, best.centroids, bins);
      binBox[b].extend(r.box);
      ++binCount[b];
    }
    Aabb acc;
    for (uint32_t b = bins; b-- > 0;) {
      acc.extend(binBox[b]);
      rightBox[b] = acc;
    }
    Aabb leftBox;
    uint32_t nLeft = 0;
    for (uint32_t b = 0; b + 1 < bins; ++b) {
      leftBox.extend(binBox[b]);
      nLeft += binCount[b];
      const uint32_t nRight = uint32_t(refs.size()) - nLeft;
      if (nLeft == 0 || nRight == 0) continue;
      const float weighted = leftBox.surfaceArea() * float(nLeft) + rightBox[b + 1].surfaceArea() * float(nRight);
      const float cost = config.traversalCost + config.intersectionCost * (area > 0.0f ? weighted / area : 0.0f);
      if (cost < best.cost) {
        best.cost = cost;
        best.axis = axis;
        best.bin = b;
        best.left = leftBox;
        best.right = rightBox[b + 1];
      }
    }
  }
  return best;
}

void applyObjectSplit(const BvhObjectSplit& split, std::span<const BvhBuildRef> refs, const BvhStackConfig& config,
                      std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right) {
  const uint32_t bins = std::max(2u, config.bins);
  for (const BvhBuildRef& r : refs)
    (binOf(r, split.axis, split.centroids, bins) <= split.bin ? left : right).push_back(r);
}

}  // namespace passtrace
