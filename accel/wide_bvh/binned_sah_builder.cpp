#include <algorithm>
#include <array>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "accel/wide_bvh/binary_bvh.h"

namespace passtrace {
namespace {

constexpr int kMaxBins = 64;

struct Bin {
  Aabb bounds;    // of the triangles
  Aabb centroids; // of their centroids: the children's centroid bounds without another pass
  uint32_t count = 0;
  void add(const Bin& o) {
    bounds.extend(o.bounds);
    centroids.extend(o.centroids);
    count += o.count;
  }
};

struct Bins {
  std::array<std::array<Bin, kMaxBins>, 3> axis;
  void add(const Bins& o, int n) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < n; ++b) axis[a][b].add(o.axis[a][b]);
  }
};

// Maps a centroid coordinate to its bin; the partition uses the same function
// so that it agrees with the counts the split was chosen from.
struct Binner {
  glm::vec3 origin, scale;
  int bins;
  Binner(const Aabb& cb, int n) : origin(cb.min), bins(n) {
    const glm::vec3 e = cb.extent();
    for (int a = 0; a < 3; ++a) scale[a] = e[a] > 0.0f ? float(n) * (1.0f - 1e-6f) / e[a] : 0.0f;
  }
  int bin(float c, int a) const {
    const int b = int((c - origin[a]) * scale[a]);
    return std::clamp(b, 0, bins - 1);
  }
};

class Builder {
public:
  Builder(std::span<const Triangle> tris, const SahBuildConfig& config, BinaryBvh& out)
      : config_(config), out_(out), bins_(std::clamp(config.bins, 2, kMaxBins)) {
    const size_t n = tris.size();
    bounds_.resize(n);
    centroids_.resize(n);
    out.prims.resize(n);
    struct Reduce {
      Aabb b, c;
    };
    const Reduce root = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 8192), Reduce{},
        [&](const tbb::blocked_range<size_t>& r, Reduce acc) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            bounds_[i] = tris[i].bounds();
            centroids_[i] = bounds_[i].center();
            out.prims[i] = uint32_t(i);
            acc.b.extend(bounds_[i]);
            acc.c.extend(centroids_[i]);
          }
          return acc;
        },
        [](Reduce a, const Reduce& b) {
          a.b.extend(b.b);
          a.c.extend(b.c);
          return a;
        });
    out.nodes.resize(n == 0 ? 0 : 2 * n - 1);
    if (n == 0) return;
    out.nodes[0].bounds = root.b;
    next_ = 1;
    build(0, 0, uint32_t(n), root.c);
    out.nodes.resize(next_.load());
  }

private:
  void makeLeaf(uint32_t node, uint32_t begin, uint32_t end) {
    out_.nodes[node].first = begin;
    out_.nodes[node].count = end - begin;
  }

  Bins binRange(uint32_t begin, uint32_t end, const Binner& binner) const {
    const auto fill = [&](uint32_t b, uint32_t e, Bins& bins) {
      for (uint32_t i = b; i < e; ++i) {
        const uint32_t p = out_.prims[i];
        for (int a = 0; a < 3; ++a) {
          Bin& bin = bins.axis[a][binner.bin(centroids_[p][a], a)];
          bin.bounds.extend(bounds_[p]);
          bin.centroids.extend(centroids_[p]);
          ++bin.count;
        }
      }
    };
    if (end - begin < 65536) {
      Bins bins;
      fill(begin, end, bins);
      return bins;
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, 16384), Bins{},
        [&](const tbb::blocked_range<uint32_t>& r, Bins acc) {
          fill(r.begin(), r.end(), acc);
          return acc;
        },
        [&](Bins a, const Bins& b) {
          a.add(b, bins_);
          return a;
        });
  }

  void build(uint32_t node, uint32_t begin, uint32_t end, const Aabb& centroidBounds) {
    const uint32_t n = end - begin;
    const Aabb& bounds = out_.nodes[node].bounds;
    if (n <= 1) return makeLeaf(node, begin, end);
    const glm::vec3 ce = centroidBounds.extent();
    const float leafCost = config_.intersectionCost * float(n);
    uint32_t mid = 0;
    Aabb leftBounds, rightBounds, leftCentroids, rightCentroids;
    if (!(ce.x > 0.0f || ce.y > 0.0f || ce.z > 0.0f)) {
      // All centroids at one point: no plane separates them; halve the list.
      if (n <= config_.maxLeafSize) return makeLeaf(node, begin, end);
      mid = begin + n / 2;
      for (uint32_t i = begin; i < end; ++i) {
        Aabb& b = i < mid ? leftBounds : rightBounds;
        b.extend(bounds_[out_.prims[i]]);
      }
      leftCentroids = rightCentroids = centroidBounds;
    } else {
      const Binner binner(centroidBounds, bins_);
      const Bins bins = binRange(begin, end, binner);
      float bestCost = kInfinity;
      int bestAxis = -1, bestSplit = 0;
      for (int a = 0; a < 3; ++a) {
        if (!(ce[a] > 0.0f)) continue;
        const auto& axis = bins.axis[a];
        // Right-to-left: the area and count of bins [b, bins).
        std::array<float, kMaxBins> rightArea{};
        std::array<uint32_t, kMaxBins> rightCount{};
        Aabb acc;
        uint32_t count = 0;
        for (int b = bins_ - 1; b > 0; --b) {
          acc.extend(axis[b].bounds);
          count += axis[b].count;
          rightArea[b] = acc.surfaceArea();
          rightCount[b] = count;
        }
        acc = Aabb{};
        count = 0;
        for (int b = 1; b < bins_; ++b) {
          acc.extend(axis[b - 1].bounds);
          count += axis[b - 1].count;
          if (count == 0 || rightCount[b] == 0) continue;
          const float cost = acc.surfaceArea() * float(count) + rightArea[b] * float(rightCount[b]);
          if (cost < bestCost) bestCost = cost, bestAxis = a, bestSplit = b;
        }
      }
      const float area = bounds.surfaceArea();
      const float splitCost = config_.traversalCost +
                              (area > 0.0f ? config_.intersectionCost * bestCost / area : leafCost);
      // Some axis has extent, so its first and last bins both hold centroids: bestAxis >= 0.
      if (n <= config_.maxLeafSize && splitCost >= leafCost) return makeLeaf(node, begin, end);
      for (int b = 0; b < bins_; ++b) {
        const Bin& bin = bins.axis[bestAxis][b];
        if (b < bestSplit) {
          leftBounds.extend(bin.bounds);
          leftCentroids.extend(bin.centroids);
        } else {
          rightBounds.extend(bin.bounds);
          rightCentroids.extend(bin.centroids);
        }
      }
      uint32_t* first = out_.prims.data() + begin;
      uint32_t* middle = std::partition(first, out_.prims.data() + end, [&](uint32_t p) {
        return binner.bin(centroids_[p][bestAxis], bestAxis) < bestSplit;
      });
      mid = begin + uint32_t(middle - first);
    }
    const uint32_t left = next_.fetch_add(2);
    out_.nodes[node].first = left;
    out_.nodes[node].count = 0;
    out_.nodes[left].bounds = leftBounds;
    out_.nodes[left + 1].bounds = rightBounds;
    if (n > config_.parallelGrain) {
      tbb::parallel_invoke([&] { build(left, begin, mid, leftCentroids); },
                           [&] { build(left + 1, mid, end, rightCentroids); });
    } else {
      build(left, begin, mid, leftCentroids);
      build(left + 1, mid, end, rightCentroids);
    }
  }

  const SahBuildConfig& config_;
  BinaryBvh& out_;
  int bins_;
  std::vector<Aabb> bounds_;
  std::vector<glm::vec3> centroids_;
  std::atomic<uint32_t> next_{0};
};

}  // namespace

BinaryBvh buildBinnedSahBvh(std::span<const Triangle> tris, const SahBuildConfig& config) {
  BinaryBvh bvh;
  Builder(tris, config, bvh);
  return bvh;
}

double bvhSahCost(const BinaryBvh& bvh, const SahBuildConfig& config) {
  if (bvh.nodes.empty()) return 0.0;
  const double rootArea = bvh.nodes[0].bounds.surfaceArea();
  double cost = 0.0;
  for (const BinaryBvhNode& node : bvh.nodes) {
    const double w = rootArea > 0.0 ? node.bounds.surfaceArea() / rootArea : 1.0;
    cost += node.leaf() ? config.intersectionCost * node.count * w : config.traversalCost * w;
  }
  return cost;
}

uint32_t bvhDepth(const BinaryBvh& bvh) {
  if (bvh.nodes.empty()) return 0;
  uint32_t depth = 0;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 1u}};  // explicit work stack: (node, level)
  while (!stack.empty()) {
    const auto [node, level] = stack.back();
    stack.pop_back();
    depth = std::max(depth, level);
    if (!bvh.nodes[node].leaf()) {
      stack.push_back({bvh.nodes[node].first, level + 1});
      stack.push_back({bvh.nodes[node].first + 1, level + 1});
    }
  }
  return depth;
}

}  // namespace passtrace
