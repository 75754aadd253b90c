// The binned SAH builder (Wald, "On fast construction of SAH-based bounding
// volume hierarchies", 2007): every axis binned at once, each bin keeping its
// triangles' bounds and their centroids' bounds (so children know their
// centroid bounds without another pass), split where the SAH is least. Large
// nodes bin in parallel and their two halves build as parallel tasks.
#include <algorithm>
#include <atomic>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "accel/wide_bvh/binary_bvh.h"

namespace passtrace {
namespace {

constexpr int kMaxBins = 32;

// A box as two 4-float vectors (the 4th lane unused; GCC/Clang generic
// vectors, so any target gets its own SIMD min/max). glm's min/max on floats
// call fmax and were a tenth of the build; scalar arrays did not vectorise.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = int __attribute__((vector_size(16)));

struct alignas(16) Box4 {
  Float4 lo, hi;
  static Box4 empty() {
    return {Float4{kInfinity, kInfinity, kInfinity, 0.0f}, Float4{-kInfinity, -kInfinity, -kInfinity, 0.0f}};
  }
  void extend(const Box4& b) {
    lo = b.lo < lo ? b.lo : lo;
    hi = b.hi > hi ? b.hi : hi;
  }
  float area() const {
    const Float4 e = hi - lo;
    return e[0] < 0.0f ? 0.0f : 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
  Aabb aabb() const { return Aabb{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
};

// A triangle's box; its centroid is computed where needed, as Aabb::center()
// rounds it: keeping it too doubled the bytes the binning and the partitions
// read per triangle.
struct Prim {
  Box4 box;
  Float4 centroid() const { return 0.5f * (box.lo + box.hi); }
  Box4 centroidBox() const {
    const Float4 c = centroid();
    return {c, c};
  }
};

// The builder's node: written once when its parent splits, so its storage is
// left uninitialised (2n - 1 of them, most never touched).
struct RawNode {
  Box4 bounds;
  uint32_t first, count;
};

struct Bin {
  Box4 bounds, centroids;
  uint32_t count;
};

struct Bins {
  int n = 0;
  Bin axis[3][kMaxBins];
  explicit Bins(int bins) : n(bins) {
    for (auto& a : axis)
      for (int b = 0; b < n; ++b) a[b] = Bin{Box4::empty(), Box4::empty(), 0};
  }
  void add(const Bins& o) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < n; ++b) {
        axis[a][b].bounds.extend(o.axis[a][b].bounds);
        axis[a][b].centroids.extend(o.axis[a][b].centroids);
        axis[a][b].count += o.axis[a][b].count;
      }
  }
};

// Maps centroids to bins; the partition uses the same function so that it
// agrees with the counts the split was chosen from.
struct Binner {
  Float4 origin, scale;
  int bins;
  Binner(const Box4& cb, int n) : bins(n) {
    origin = cb.lo;
    for (int a = 0; a < 4; ++a) {
      const float e = cb.hi[a] - cb.lo[a];
      scale[a] = a < 3 && e > 0.0f ? float(n) * (1.0f - 1e-6f) / e : 0.0f;
    }
  }
  Int4 bins3(const Float4& c) const {
    const Int4 b = __builtin_convertvector((c - origin) * scale, Int4);
    const Int4 zero = {0, 0, 0, 0}, last = {bins - 1, bins - 1, bins - 1, bins - 1};
    const Int4 low = b < zero ? zero : b;
    return low > last ? last : low;
  }
  int bin(const Float4& c, int a) const { return bins3(c)[a]; }
};

class Builder {
public:
  Builder(std::span<const Triangle> tris, const SahBuildConfig& config, SahBinaryBvh& out)
      : config_(config), out_(out), bins_(std::clamp(config.bins, 2, kMaxBins)) {
    const size_t n = tris.size();
    prims_ = std::make_unique_for_overwrite<Prim[]>(n);
    out.prims.resize(n);
    struct Reduce {
      Box4 b = Box4::empty(), c = Box4::empty();
    };
    const Reduce root = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 8192), Reduce{},
        [&](const tbb::blocked_range<size_t>& r, Reduce acc) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            const Aabb b = tris[i].bounds();
            prims_[i].box = Box4{Float4{b.min.x, b.min.y, b.min.z, 0.0f}, Float4{b.max.x, b.max.y, b.max.z, 0.0f}};
            out.prims[i] = uint32_t(i);
            acc.b.extend(prims_[i].box);
            acc.c.extend(prims_[i].centroidBox());
          }
          return acc;
        },
        [](Reduce a, const Reduce& b) {
          a.b.extend(b.b);
          a.c.extend(b.c);
          return a;
        });
    if (n == 0) return;
    nodes_ = std::make_unique_for_overwrite<RawNode[]>(2 * n - 1);
    nodes_[0].bounds = root.b;
    next_ = 1;
    build(0, 0, uint32_t(n), root.b, root.c);
    out.nodes.resize(next_.load());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.nodes.size(), 16384), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        out.nodes[i] = SahBinaryBvhNode{nodes_[i].bounds.aabb(), nodes_[i].first, nodes_[i].count};
    });
  }

private:
  void makeLeaf(uint32_t node, uint32_t begin, uint32_t end) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
  }

  void binRange(uint32_t begin, uint32_t end, const Binner& binner, Bins& bins) const {
    const auto fill = [&](uint32_t b, uint32_t e, Bins& into) {
      for (uint32_t i = b; i < e; ++i) {
        const Prim& p = prims_[out_.prims[i]];
        const Box4 centroid = p.centroidBox();
        const Int4 b = binner.bins3(centroid.lo);
        for (int a = 0; a < 3; ++a) {
          Bin& bin = into.axis[a][b[a]];
          bin.bounds.extend(p.box);
          bin.centroids.extend(centroid);
          ++bin.count;
        }
      }
    };
    if (end - begin < 65536) return fill(begin, end, bins);
    bins = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, 16384), Bins(binner.bins),
        [&](const tbb::blocked_range<uint32_t>& r, Bins acc) {
          fill(r.begin(), r.end(), acc);
          return acc;
        },
        [&](Bins a, const Bins& b) {
          a.add(b);
          return a;
        });
  }

  void build(uint32_t node, uint32_t begin, uint32_t end, const Box4& bounds, const Box4& centroidBounds) {
    const uint32_t n = end - begin;
    if (n <= config_.leafSize) return makeLeaf(node, begin, end);
    const float ce[3] = {centroidBounds.hi[0] - centroidBounds.lo[0], centroidBounds.hi[1] - centroidBounds.lo[1],
                         centroidBounds.hi[2] - centroidBounds.lo[2]};
    const float leafCost = config_.intersectionCost * float(n);
    uint32_t mid = 0;
    Box4 leftBounds = Box4::empty(), rightBounds = Box4::empty();
    Box4 leftCentroids = Box4::empty(), rightCentroids = Box4::empty();
    if (!(ce[0] > 0.0f || ce[1] > 0.0f || ce[2] > 0.0f)) {
      // All centroids at one point: no plane separates them; halve the list.
      if (n <= config_.maxLeafSize) return makeLeaf(node, begin, end);
      mid = begin + n / 2;
      for (uint32_t i = begin; i < end; ++i) (i < mid ? leftBounds : rightBounds).extend(prims_[out_.prims[i]].box);
      leftCentroids = rightCentroids = centroidBounds;
    } else {
      // Fewer bins than triangles buys nothing: small nodes bin with about one per triangle.
      const int binCount = int(std::min<uint32_t>(uint32_t(bins_), std::max<uint32_t>(n, 4u)));
      const Binner binner(centroidBounds, binCount);
      Bins bins(binCount);
      binRange(begin, end, binner, bins);
      float bestCost = kInfinity;
      int bestAxis = -1, bestSplit = 0;
      for (int a = 0; a < 3; ++a) {
        if (!(ce[a] > 0.0f)) continue;
        const Bin* axis = bins.axis[a];
        // Right to left: the area and count of bins [b, binCount).
        float rightArea[kMaxBins];
        uint32_t rightCount[kMaxBins];
        Box4 acc = Box4::empty();
        uint32_t count = 0;
        for (int b = binCount - 1; b > 0; --b) {
          acc.extend(axis[b].bounds);
          count += axis[b].count;
          rightArea[b] = acc.area();
          rightCount[b] = count;
        }
        acc = Box4::empty();
        count = 0;
        for (int b = 1; b < binCount; ++b) {
          acc.extend(axis[b - 1].bounds);
          count += axis[b - 1].count;
          if (count == 0 || rightCount[b] == 0) continue;
          const float cost = acc.area() * float(count) + rightArea[b] * float(rightCount[b]);
          if (cost < bestCost) bestCost = cost, bestAxis = a, bestSplit = b;
        }
      }
      // Some axis has extent, so its first and last bins both hold centroids;
      // bestAxis < 0 only when every cost overflowed (boxes beyond about 1e19).
      if (bestAxis < 0) return medianSplit(node, begin, end, ce);
      const float area = bounds.area();
      const float splitCost =
          config_.traversalCost + (area > 0.0f ? config_.intersectionCost * bestCost / area : leafCost);
      if (n <= config_.maxLeafSize && splitCost >= leafCost) return makeLeaf(node, begin, end);
      for (int b = 0; b < binCount; ++b) {
        const Bin& bin = bins.axis[bestAxis][b];
        (b < bestSplit ? leftBounds : rightBounds).extend(bin.bounds);
        (b < bestSplit ? leftCentroids : rightCentroids).extend(bin.centroids);
      }
      uint32_t* first = out_.prims.data() + begin;
      uint32_t* middle = std::partition(first, out_.prims.data() + end, [&](uint32_t p) {
        return binner.bin(prims_[p].centroid(), bestAxis) < bestSplit;
      });
      mid = begin + uint32_t(middle - first);
    }
    const uint32_t left = next_.fetch_add(2);
    nodes_[node].first = left;
    nodes_[node].count = 0;
    nodes_[left].bounds = leftBounds;
    nodes_[left + 1].bounds = rightBounds;
    if (n > config_.parallelGrain) {
      tbb::parallel_invoke([&] { build(left, begin, mid, leftBounds, leftCentroids); },
                           [&] { build(left + 1, mid, end, rightBounds, rightCentroids); });
    } else {
      build(left, begin, mid, leftBounds, leftCentroids);
      build(left + 1, mid, end, rightBounds, rightCentroids);
    }
  }

  // Halves the list at the median centroid of the widest axis: where areas
  // overflow float, SAH cannot rank the splits, but a tree must still be built.
  void medianSplit(uint32_t node, uint32_t begin, uint32_t end, const float (&ce)[3]) {
    const int axis = ce[0] >= ce[1] && ce[0] >= ce[2] ? 0 : (ce[1] >= ce[2] ? 1 : 2);
    uint32_t* first = out_.prims.data() + begin;
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(first, out_.prims.data() + mid, out_.prims.data() + end,
                     [&](uint32_t a, uint32_t b) { return prims_[a].centroid()[axis] < prims_[b].centroid()[axis]; });
    Box4 boxes[2] = {Box4::empty(), Box4::empty()}, centroids[2] = {Box4::empty(), Box4::empty()};
    for (uint32_t i = begin; i < end; ++i) {
      boxes[i >= mid].extend(prims_[out_.prims[i]].box);
      centroids[i >= mid].extend(prims_[out_.prims[i]].centroidBox());
    }
    const uint32_t left = next_.fetch_add(2);
    nodes_[node].first = left;
    nodes_[node].count = 0;
    nodes_[left].bounds = boxes[0];
    nodes_[left + 1].bounds = boxes[1];
    build(left, begin, mid, boxes[0], centroids[0]);
    build(left + 1, mid, end, boxes[1], centroids[1]);
  }

  const SahBuildConfig& config_;
  SahBinaryBvh& out_;
  int bins_;
  std::unique_ptr<Prim[]> prims_;
  std::unique_ptr<RawNode[]> nodes_;
  std::atomic<uint32_t> next_{0};
};

}  // namespace

SahBinaryBvh buildBinnedSahBvh(std::span<const Triangle> tris, const SahBuildConfig& config) {
  SahBinaryBvh bvh;
  Builder(tris, config, bvh);
  return bvh;
}

double bvhSahCost(const SahBinaryBvh& bvh, const SahBuildConfig& config) {
  if (bvh.nodes.empty()) return 0.0;
  const double rootArea = bvh.nodes[0].bounds.surfaceArea();
  // Summed in tree order, not array order: parallel builds number nodes in
  // task order, and the sum must not depend on it.
  double cost = 0.0;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const SahBinaryBvhNode& node = bvh.nodes[stack.back()];
    stack.pop_back();
    const double w = rootArea > 0.0 ? node.bounds.surfaceArea() / rootArea : 1.0;
    cost += node.leaf() ? config.intersectionCost * node.count * w : config.traversalCost * w;
    if (!node.leaf()) stack.insert(stack.end(), {node.first + 1, node.first});
  }
  return cost;
}

uint32_t bvhDepth(const SahBinaryBvh& bvh) {
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
