#include "accel/kd/kd_binned_builder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "accel/kd/kd_build_driver.h"

namespace passtrace {
namespace {

// Per axis, references starting (min) and ending (max) in each bin.
struct EdgeBins {
  std::array<std::array<uint32_t, kKdBins>, 3> min{}, max{};

  void add(const EdgeBins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < kKdBins; ++b) min[a][b] += o.min[a][b], max[a][b] += o.max[a][b];
  }
};

// Bin of coordinate x: floor((x - lo) * scale), clamped (a clipped bound
// lies inside the voxel, but rounding may put it a hair outside a bin
// range, and a denormal-thin voxel makes scale infinite).
int binOf(float x, float lo, float scale, int binCount) {
  const float b = (x - lo) * scale;
  if (!(b > 0.0f)) return 0;  // NaN too
  return b < float(binCount) ? static_cast<int>(b) : binCount - 1;
}

void binRefs(std::span<const KdRef> refs, const Aabb& voxel, const glm::vec3& scale, const bool* axes, int binCount,
             EdgeBins& bins) {
  for (const KdRef& r : refs)
    for (int a = 0; a < 3; ++a) {
      if (!axes[a]) continue;
      ++bins.min[a][binOf(r.bounds.min[a], voxel.min[a], scale[a], binCount)];
      ++bins.max[a][binOf(r.bounds.max[a], voxel.min[a], scale[a], binCount)];
    }
}

// kKdBins, or for a node of n < kKdBins / 2 references the power of two
// at or above 2n (at least 4): n references have at most 2n distinct bounds,
// and the boundary scan, not the binning, is most of a small node's time.
int binsFor(size_t n) {
  if (n >= size_t(kKdBins / 2)) return kKdBins;
  return std::max(4, static_cast<int>(std::bit_ceil(2 * n)));
}

KdSplit findBinnedSplit(std::span<const KdRef> refs, const Aabb& voxel, const KdBuildConfig& config,
                        float minThickness) {
  KdSplit best;
  const glm::vec3 e = voxel.extent();
  const float area = voxel.surfaceArea();
  if (!(area > 0.0f)) return best;  // a point or segment voxel: nothing to weigh
  const bool axes[3] = {e.x > 0.0f, e.y > 0.0f, e.z > 0.0f};
  const int binCount = binsFor(refs.size());
  glm::vec3 scale(0.0f);
  for (int a = 0; a < 3; ++a)
    if (axes[a]) scale[a] = float(binCount) / e[a];

  EdgeBins bins;
  if (refs.size() < kKdParallelSweepRefs) {
    binRefs(refs, voxel, scale, axes, binCount, bins);
  } else {  // fixed chunks; integer sums, so any thread count gives the same bins
    std::vector<EdgeBins> partial(kKdSweepChunks);
    const size_t chunk = (refs.size() + kKdSweepChunks - 1) / kKdSweepChunks;
    tbb::parallel_for(size_t(0), kKdSweepChunks, [&](size_t c) {
      const size_t begin = std::min(refs.size(), c * chunk), end = std::min(refs.size(), begin + chunk);
      binRefs(refs.subspan(begin, end - begin), voxel, scale, axes, binCount, partial[c]);
    });
    for (const EdgeBins& p : partial) bins.add(p);
  }

  // Constants in locals: the cost loop below stores to an array, and the
  // compiler would otherwise reload them from `config` on every boundary.
  const float traversal = config.traversalCost, emptyBonus = config.emptyBonus;
  const float perArea = 2.0f * config.intersectionCost / area;
  const auto n = static_cast<float>(refs.size());
  for (int axis = 0; axis < 3; ++axis) {
    if (!axes[axis]) continue;
    const float lo = voxel.min[axis], hi = voxel.max[axis], width = e[axis];
    const float a1 = e[(axis + 1) % 3], a2 = e[(axis + 2) % 3];
    const float cross = a1 * a2, sideArea = width * (a1 + a2);
    // Boundary b lies between bins b - 1 and b. Left of it: the min-bins
    // before b (exclusive scan); right of it: the max-bins from b on (an
    // inclusive scan from the far end, here n minus the max-bins before b).
    alignas(32) float left[kKdBins], right[kKdBins], cost[kKdBins];
    uint32_t minBefore = 0, maxBefore = 0;
    for (int b = 0; b < binCount; ++b) {
      left[b] = float(minBefore);
      right[b] = n - float(maxBefore);
      minBefore += bins.min[axis][b];
      maxBefore += bins.max[axis][b];
    }
    // Every boundary's SAH in one branch-free loop the compiler vectorises
    // (b = 0, the voxel's face, is computed and never chosen).
    const float binWidth = 1.0f / float(binCount);  // a power of two: exact
    for (int b = 0; b < binCount; ++b) {
      const float t = float(b) * binWidth;
      const float areaLeft = cross + t * sideArea, areaRight = cross + (1.0f - t) * sideArea;
      cost[b] = perArea * (areaLeft * left[b] + areaRight * right[b]);
    }
    for (int b = 0; b < binCount; ++b) {
      if (emptyBonus != 0.0f && (left[b] == 0.0f || right[b] == 0.0f)) cost[b] *= 1.0f - emptyBonus;
      cost[b] += traversal;
    }
    for (int b = 1; b < binCount; ++b) {
      if (!(cost[b] < best.cost)) continue;
      const float p = lo + width * (float(b) * binWidth);
      if (p > lo && p < hi && p - lo >= minThickness && hi - p >= minThickness) best = KdSplit{axis, p, cost[b]};
    }
  }
  return best;
}

}  // namespace

KdTree buildKdTreeBinned(std::span<const Triangle> tris, const KdBuildConfig& config) {
  return buildKdTreeWith(tris, config, findBinnedSplit);
}

}  // namespace passtrace
