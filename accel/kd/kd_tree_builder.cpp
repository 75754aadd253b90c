#include "accel/kd/kd_tree_builder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>
#include <vector>

#include "accel/kd/kd_build_driver.h"

namespace passtrace {

int kdDefaultMaxDepth(size_t triangleCount) {
  if (triangleCount <= 1) return 8;
  return static_cast<int>(std::lround(8.0 + 1.3 * std::log2(static_cast<double>(triangleCount))));
}

int kdEffectiveMaxDepth(const KdBuildConfig& config, size_t triangleCount) {
  const int depth = config.maxDepth > 0 ? config.maxDepth : kdDefaultMaxDepth(triangleCount);
  return std::clamp(depth, 0, kKdDepthLimit);
}

namespace {

// Floats as unsigned keys that sort in the same order (negative floats have
// all bits flipped, positive ones their sign bit set). -0 is made +0 first
// so equal floats get equal keys.
uint32_t sortKey(float f) {
  const auto bits = std::bit_cast<uint32_t>(f + 0.0f);
  return (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;
}
float keyFloat(uint32_t key) { return std::bit_cast<float>((key & 0x80000000u) ? key & 0x7FFFFFFFu : ~key); }

// LSD radix sort (11-bit digits, three passes) for large arrays: the
// candidate sort is most of the build time, and this makes it linear.
void sortKeys(std::vector<uint32_t>& keys, std::vector<uint32_t>& scratch) {
  const size_t n = keys.size();
  if (n < 512) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  constexpr int kBits = 11, kBuckets = 1 << kBits;
  std::vector<uint32_t> counts(3 * kBuckets, 0);
  for (const uint32_t k : keys)
    for (int d = 0; d < 3; ++d) ++counts[d * kBuckets + ((k >> (d * kBits)) & (kBuckets - 1))];
  scratch.resize(n);
  for (int d = 0; d < 3; ++d) {
    uint32_t* c = counts.data() + d * kBuckets;
    uint32_t sum = 0;
    for (int b = 0; b < kBuckets; ++b) sum += std::exchange(c[b], sum);
    for (const uint32_t k : keys) scratch[c[(k >> (d * kBits)) & (kBuckets - 1)]++] = k;
    keys.swap(scratch);
  }
}

struct Scratch {
  std::vector<uint32_t> mins, maxs, tmp;
};

// Finds the cheapest plane over all three axes. Candidates are the clipped
// bounds' faces strictly inside the voxel (a plane on the voxel's face
// leaves one child with everything). With the closed-voxel rule,
// N_L(p) = #{min <= p} and N_R(p) = #{max >= p}: one merged walk over the
// sorted mins and maxes.
KdSplit findSplit(std::span<const KdRef> refs, const Aabb& voxel, const KdBuildConfig& config, float minThickness) {
  // Small nodes, by far the most, reuse their thread's arrays; a large node
  // gets its own, so that no thread keeps the root's size after the build.
  thread_local Scratch reused;
  Scratch own;
  Scratch& s = refs.size() < kKdParallelSweepRefs ? reused : own;
  KdSplit best;
  const glm::vec3 e = voxel.extent();
  const float area = voxel.surfaceArea();
  if (!(area > 0.0f)) return best;  // a point or segment voxel: nothing to weigh
  const float invArea = 1.0f / area;
  const size_t n = refs.size();
  s.mins.resize(n);
  s.maxs.resize(n);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(e[axis] > 0.0f)) continue;
    for (size_t i = 0; i < n; ++i) {
      s.mins[i] = sortKey(refs[i].bounds.min[axis]);
      s.maxs[i] = sortKey(refs[i].bounds.max[axis]);
    }
    sortKeys(s.mins, s.tmp);
    sortKeys(s.maxs, s.tmp);
    const uint32_t* mins = s.mins.data();
    const uint32_t* maxs = s.maxs.data();
    const uint32_t lo = sortKey(voxel.min[axis]), hi = sortKey(voxel.max[axis]);
    const float loF = voxel.min[axis], hiF = voxel.max[axis];
    const float a1 = e[(axis + 1) % 3], a2 = e[(axis + 2) % 3];
    const float cross = a1 * a2, perimeter = a1 + a2;
    size_t i = 0, j = 0;  // mins consumed (<= p), maxs consumed (< p)
    while (i < n || j < n) {
      const uint32_t p = (i < n && (j >= n || mins[i] <= maxs[j])) ? mins[i] : maxs[j];
      while (i < n && mins[i] <= p) ++i;
      const float pF = keyFloat(p);
      if (p > lo && p < hi && pF - loF >= minThickness && hiF - pF >= minThickness) {
        const size_t nLeft = i, nRight = n - j;
        const float areaLeft = 2.0f * (cross + (pF - loF) * perimeter);
        const float areaRight = 2.0f * (cross + (hiF - pF) * perimeter);
        const float bonus = (nLeft == 0 || nRight == 0) ? config.emptyBonus : 0.0f;
        const float cost = config.traversalCost + config.intersectionCost * (1.0f - bonus) * invArea *
                                                      (areaLeft * float(nLeft) + areaRight * float(nRight));
        if (cost < best.cost) best = KdSplit{axis, pF, cost};
      }
      while (j < n && maxs[j] <= p) ++j;
    }
  }
  return best;
}

}  // namespace

KdTree buildKdTree(std::span<const Triangle> tris, const KdBuildConfig& config) {
  return buildKdTreeWith(tris, config, findSplit);
}

}  // namespace passtrace
