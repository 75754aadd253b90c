// The exact full-sweep SAH builder: at every node the triangles are sorted by
// centroid on each axis and every position between two of them is priced.
// O(n log^2 n); the reference that binned_sah_builder.cpp is measured against.
#include <algorithm>
#include <atomic>
#include <numeric>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "accel/wide_bvh/binary_bvh.h"

namespace passtrace {
namespace {

class ExactBuilder {
public:
  ExactBuilder(std::span<const Triangle> tris, const SahBuildConfig& config, SahBinaryBvh& out)
      : config_(config), out_(out) {
    const size_t n = tris.size();
    bounds_.resize(n);
    centroids_.resize(n);
    out.prims.resize(n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      bounds_[i] = tris[i].bounds();
      centroids_[i] = bounds_[i].center();
    });
    std::iota(out.prims.begin(), out.prims.end(), 0u);
    if (n == 0) return;
    out.nodes.resize(2 * n - 1);
    Aabb root;
    for (const Aabb& b : bounds_) root.extend(b);
    out.nodes[0].bounds = root;
    next_ = 1;
    build(0, 0, uint32_t(n));
    out.nodes.resize(next_.load());
  }

private:
  void build(uint32_t node, uint32_t begin, uint32_t end) {
    const uint32_t n = end - begin;
    if (n <= config_.leafSize) {
      out_.nodes[node].first = begin, out_.nodes[node].count = n;
      return;
    }
    std::vector<uint32_t> order[3];
    std::vector<float> rightArea(n);
    float bestCost = kInfinity;
    int bestAxis = 0;
    uint32_t bestSplit = 0;  // left = first bestSplit triangles of the sorted order
    for (int a = 0; a < 3; ++a) {
      order[a].assign(out_.prims.begin() + begin, out_.prims.begin() + end);
      std::sort(order[a].begin(), order[a].end(), [&](uint32_t x, uint32_t y) {
        const float cx = centroids_[x][a], cy = centroids_[y][a];
        return cx < cy || (cx == cy && x < y);
      });
      Aabb acc;
      for (uint32_t i = n; i-- > 1;) {
        acc.extend(bounds_[order[a][i]]);
        rightArea[i] = acc.surfaceArea();
      }
      acc = Aabb{};
      for (uint32_t i = 1; i < n; ++i) {
        acc.extend(bounds_[order[a][i - 1]]);
        const float cost = acc.surfaceArea() * float(i) + rightArea[i] * float(n - i);
        if (cost < bestCost) bestCost = cost, bestAxis = a, bestSplit = i;
      }
    }
    const float area = out_.nodes[node].bounds.surfaceArea();
    const float leafCost = config_.intersectionCost * float(n);
    const float splitCost =
        config_.traversalCost + (area > 0.0f ? config_.intersectionCost * bestCost / area : leafCost);
    if (n <= config_.maxLeafSize && splitCost >= leafCost) {
      out_.nodes[node].first = begin, out_.nodes[node].count = n;
      return;
    }
    std::copy(order[bestAxis].begin(), order[bestAxis].end(), out_.prims.begin() + begin);
    Aabb leftBounds, rightBounds;
    for (uint32_t i = 0; i < n; ++i) (i < bestSplit ? leftBounds : rightBounds).extend(bounds_[order[bestAxis][i]]);
    for (auto& o : order) std::vector<uint32_t>().swap(o);
    const uint32_t mid = begin + bestSplit;
    const uint32_t left = next_.fetch_add(2);
    out_.nodes[node].first = left;
    out_.nodes[node].count = 0;
    out_.nodes[left].bounds = leftBounds;
    out_.nodes[left + 1].bounds = rightBounds;
    if (n > config_.parallelGrain) {
      tbb::parallel_invoke([&] { build(left, begin, mid); }, [&] { build(left + 1, mid, end); });
    } else {
      build(left, begin, mid);
      build(left + 1, mid, end);
    }
  }

  const SahBuildConfig& config_;
  SahBinaryBvh& out_;
  std::vector<Aabb> bounds_;
  std::vector<glm::vec3> centroids_;
  std::atomic<uint32_t> next_{0};
};

}  // namespace

SahBinaryBvh buildExactSahBvh(std::span<const Triangle> tris, const SahBuildConfig& config) {
  SahBinaryBvh bvh;
  ExactBuilder(tris, config, bvh);
  return bvh;
}

}  // namespace passtrace
