#include "accel/dacrt/dacrt_tracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "accel/dacrt/cell_tests.h"

namespace passtrace::dacrt {
namespace {

constexpr int kMaxDepth = 64;              // deeper cells are traced naively (pLimit 1 around a shared vertex)
constexpr size_t kMeanSplitMin = 10000;    // the seed's sampled-mean split above this many triangles ...
constexpr size_t kSampleStride = 50;       // ... over every 50th triangle
constexpr size_t kEdgeTestMax = 100;       // the full triangle/box test at this many triangles or fewer
constexpr int kPacketSide = 8;             // a cone per 8x8 rays: one 64-bit mask
// The seed's cLimit (it gives none): cones flush to rays at this many or
// fewer. Measured on the bunny at 512² (docs/bench-dacrt): 4 gives the
// fewest box tests for primary cones; shadow cones, wider and less
// coherent, do best flushed early, at 16.
constexpr size_t kPrimaryConeLimit = 4;
constexpr size_t kShadowConeLimit = 16;
constexpr double kConeMargin = 1e-3;       // radians added to a cone's angle: rounding never leaves a ray out
constexpr double kWidestCone = 1.3;        // radians (75°): wider packets go ray by ray
constexpr unsigned kBandsPerThread = 2;    // screen bands per thread: stealing evens out uneven bands

struct Split {
  int axis;
  float position;
};

// What every band reads: the batch, with each ray's inverse direction.
struct Shared {
  std::span<const Triangle> tris;
  Settings settings;
  const RayBatch& batch;
  std::span<Hit> hits;
  std::span<RayStats> stats;
  std::span<glm::vec3> invDir;  // each band fills its own elements
  Aabb root;
  // Primary rays from one point: cells are visited front to back from it,
  // so a ray whose hit lies in the current cell has its closest hit and
  // retires. Other rays keep their best t and are culled by it (§3.4).
  bool frontToBack = false;
  glm::vec3 eye{0.0f};
};

// One screen band's rays traced against every triangle: the index arrays and
// pivots of Algorithm 1 (rays) and Algorithm 2 (cones).
class Band {
public:
  explicit Band(const Shared& shared) : s_(shared), rays_(shared.batch.rays) {}

  FilterStats run(size_t begin, size_t end) {
    const RayBatch& b = s_.batch;
    std::vector<uint32_t> plain;
    for (size_t e = begin; e < end; ++e) {
      if (!b.active[e]) continue;
      s_.hits[e] = Hit{rays_[e].tMax, 0.0f, 0.0f, kNoHit};
      s_.invDir[e] = safeInverse(rays_[e].direction);
    }
    if (s_.tris.empty()) return counters_;  // every ray misses: nothing to filter
    if (s_.settings.cones && b.width > 0) makeCones(begin, end, plain);
    else
      for (size_t e = begin; e < end; ++e)
        if (b.active[e]) plain.push_back(uint32_t(e));
    if (plain.empty() && cones_.empty()) return counters_;
    triIds_.resize(s_.tris.size());
    std::iota(triIds_.begin(), triIds_.end(), 0u);
    const size_t allTris = triIds_.size();
    if (!cones_.empty()) {
      packetDepth_ = int(8.0 + 1.3 * std::log2(double(std::max<size_t>(allTris, 1))));
      rayIds_.assign(memberCount_, 0);
      coneIds_.resize(cones_.size());
      std::iota(coneIds_.begin(), coneIds_.end(), 0u);
      packets(s_.root, filterCones(s_.root, coneIds_.size()), allTris, 0);
    }
    if (!plain.empty()) {
      rayIds_ = std::move(plain);
      retired_ = 0;
      rays(s_.root, filterRays(s_.root, rayIds_.size()), allTris, 0);
    }
    return counters_;
  }

private:
  // Algorithm 1 over rayIds_[retired_, rayEnd) and triIds_[0, triEnd).
  void rays(const Aabb& cell, size_t rayEnd, size_t triEnd, int depth) {
    ++counters_.nodes;
    if (rayEnd <= retired_ || triEnd == 0) return;
    // "At most" rather than the seed's "fewer than": at rLimit = pLimit = 1
    // a single ray or triangle is still traced.
    if (rayEnd - retired_ <= size_t(s_.settings.rLimit) || triEnd <= size_t(s_.settings.pLimit) ||
        depth >= kMaxDepth)
      return naive(cell, rayEnd, triEnd);
    const Split split = chooseSplit(cell, triEnd);
    if (!(split.position > cell.min[split.axis] && split.position < cell.max[split.axis]))
      return naive(cell, rayEnd, triEnd);  // a cell too thin for floats to split
    const bool lowFirst = s_.frontToBack ? s_.eye[split.axis] < split.position : majorityPositive(split.axis, rayEnd);
    for (int side = 0; side < 2; ++side) {
      const bool low = (side == 0) == lowFirst;
      const Aabb child = childCell(cell, split, low);
      const size_t childTris = filterTriangles(child, split, low, triEnd);
      if (childTris == 0) continue;
      rays(child, filterRays(child, rayEnd), childTris, depth + 1);
    }
  }

  // Algorithm 2 over coneIds_[conesRetired_, coneEnd).
  void packets(const Aabb& cell, size_t coneEnd, size_t triEnd, int depth) {
    ++counters_.nodes;
    if (coneEnd <= conesRetired_ || triEnd == 0) return;
    // Cones do not thin out as rays do: where triangles meet at a point both
    // halves keep them all and the cones with them, so packets stop at a
    // kd-tree's depth limit (8 + 1.3 log2 N) and their rays carry on.
    const size_t coneLimit = s_.frontToBack ? kPrimaryConeLimit : kShadowConeLimit;
    if (coneEnd - conesRetired_ <= coneLimit || triEnd <= size_t(s_.settings.pLimit) || depth >= packetDepth_)
      return flush(cell, coneEnd, triEnd, depth);
    const Split split = chooseSplit(cell, triEnd);
    if (!(split.position > cell.min[split.axis] && split.position < cell.max[split.axis]))
      return flush(cell, coneEnd, triEnd, depth);
    // Every cone of a band shares its apex (the eye, or the light).
    const bool lowFirst = cones_[coneIds_[conesRetired_]].apex[split.axis] < split.position;
    for (int side = 0; side < 2; ++side) {
      const bool low = (side == 0) == lowFirst;
      const Aabb child = childCell(cell, split, low);
      const size_t childTris = filterTriangles(child, split, low, triEnd);
      if (childTris == 0) continue;
      packets(child, filterCones(child, coneEnd), childTris, depth + 1);
    }
  }

  // FlushCones: the live rays of the cell's cones go through Algorithm 1;
  // those that retire there set their bits, and full cones retire.
  void flush(const Aabb& cell, size_t coneEnd, size_t triEnd, int depth) {
    size_t rayEnd = retired_;
    for (size_t k = conesRetired_; k < coneEnd; ++k) {
      const uint32_t c = coneIds_[k];
      for (int j = 0; j < 64; ++j)
        if (!(done_[c] >> j & 1u)) rayIds_[rayEnd++] = members_[size_t(c) * 64 + size_t(j)];
    }
    const size_t before = retired_;
    rays(cell, filterRays(cell, rayEnd), triEnd, depth);
    for (size_t k = before; k < retired_; ++k) {
      const uint32_t e = rayIds_[k];
      const auto [c, bit] = slotOf_[e - first_];
      done_[c] |= uint64_t(1) << bit;
    }
    for (size_t k = conesRetired_; k < coneEnd; ++k)
      if (done_[coneIds_[k]] == ~uint64_t(0)) std::swap(coneIds_[k], coneIds_[conesRetired_++]);
  }

  // Every ray against every triangle; rays with their final hit retire.
  void naive(const Aabb& cell, size_t rayEnd, size_t triEnd) {
    const TriangleTest test = s_.settings.test;
    for (size_t k = retired_; k < rayEnd; ++k) {
      const uint32_t e = rayIds_[k];
      const Ray& ray = rays_[e];
      const bool anyHit = s_.batch.anyHit[e] != 0;
      Hit& best = s_.hits[e];
      uint32_t tested = 0;
      for (size_t i = 0; i < triEnd; ++i) {
        const uint32_t id = triIds_[i];
        // Triangles come in no fixed order: a tie in t goes to the lower
        // index, as brute force's scene order gives it.
        Hit candidate = best;
        if (best.found()) candidate.t = std::nextafter(best.t, kInfinity);
        ++tested;
        if (intersectTriangle(ray.origin, ray.direction, s_.tris[id], id, candidate, test) &&
            (candidate.t < best.t || id < best.id)) {
          best = candidate;
          if (anyHit) break;
        }
      }
      counters_.rayTriangle += tested;
      s_.stats[e].triangleTests += tested;
      s_.stats[e].steps += tested;
      if (retires(e, anyHit, cell)) std::swap(rayIds_[k], rayIds_[retired_++]);
    }
  }

  bool retires(uint32_t e, bool anyHit, const Aabb& cell) const {
    const Hit& best = s_.hits[e];
    if (!best.found()) return false;
    if (anyHit) return true;
    if (!s_.frontToBack) return false;
    const glm::vec3 p = rays_[e].origin + best.t * rays_[e].direction;
    return p.x >= cell.min.x && p.x <= cell.max.x && p.y >= cell.min.y && p.y <= cell.max.y && p.z >= cell.min.z &&
           p.z <= cell.max.z;
  }

  // The seed's split: the longest axis; above 10,000 triangles the mean of
  // the clamped span midpoints of every 50th triangle, else the middle.
  Split chooseSplit(const Aabb& cell, size_t triEnd) const {
    const glm::vec3 size = cell.extent();
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    const float lo = cell.min[axis], hi = cell.max[axis];
    if (!s_.settings.medianSplit && triEnd > kMeanSplitMin) {
      double sum = 0;
      size_t count = 0;
      for (size_t i = 0; i < triEnd; i += kSampleStride) {
        const Triangle& t = s_.tris[triIds_[i]];
        const float a = std::clamp(std::min({t.v0[axis], t.v1[axis], t.v2[axis]}), lo, hi);
        const float b = std::clamp(std::max({t.v0[axis], t.v1[axis], t.v2[axis]}), lo, hi);
        sum += 0.5 * (double(a) + double(b));
        ++count;
      }
      const float mean = float(sum / double(count));
      if (mean > lo && mean < hi) return {axis, mean};
    }
    return {axis, 0.5f * (lo + hi)};
  }

  static Aabb childCell(const Aabb& cell, const Split& split, bool low) {
    Aabb child = cell;
    (low ? child.max : child.min)[split.axis] = split.position;
    return child;
  }

  // Triangles of the parent that touch the child first. They touch the
  // parent, so the split plane alone decides; the full test (its nine edge
  // axes) pays only when few remain.
  size_t filterTriangles(const Aabb& child, const Split& split, bool low, size_t triEnd) {
    counters_.triangleBox += triEnd;
    const bool full = triEnd <= kEdgeTestMax;
    const int a = split.axis;
    size_t keep = 0;
    for (size_t i = 0; i < triEnd; ++i) {
      const Triangle& t = s_.tris[triIds_[i]];
      bool in = low ? std::min({t.v0[a], t.v1[a], t.v2[a]}) <= split.position
                    : std::max({t.v0[a], t.v1[a], t.v2[a]}) >= split.position;
      if (in && full) in = triangleTouchesCell(t, child);
      if (in) std::swap(triIds_[i], triIds_[keep++]);
    }
    return keep;
  }

  // Live rays that enter the cell before their best hit (or tMax) first.
  size_t filterRays(const Aabb& cell, size_t rayEnd) {
    counters_.rayBox += rayEnd - retired_;
    size_t keep = retired_;
    for (size_t k = retired_; k < rayEnd; ++k) {
      const uint32_t e = rayIds_[k];
      ++s_.stats[e].steps;
      if (rayEntersCell(rays_[e].origin, s_.invDir[e], cell, s_.hits[e].t)) std::swap(rayIds_[k], rayIds_[keep++]);
    }
    return keep;
  }

  size_t filterCones(const Aabb& cell, size_t coneEnd) {
    counters_.coneBox += coneEnd - conesRetired_;
    size_t keep = conesRetired_;
    for (size_t k = conesRetired_; k < coneEnd; ++k)
      if (coneTouchesCell(cones_[coneIds_[k]], cell)) std::swap(coneIds_[k], coneIds_[keep++]);
    return keep;
  }

  // Secondary rays without a common origin: the child most rays head into
  // first (Reshetov's majority, as the seed's §3.4).
  bool majorityPositive(int axis, size_t rayEnd) const {
    size_t positive = 0;
    for (size_t k = retired_; k < rayEnd; ++k) positive += s_.invDir[rayIds_[k]][axis] > 0.0f;
    return 2 * positive >= rayEnd - retired_;
  }

  // A cone per 8x8 pixels of the band: primary rays from the eye, shadow
  // rays from the light. Other rays, and packets too wide for a cone, are
  // traced as plain rays.
  void makeCones(size_t begin, size_t end, std::vector<uint32_t>& plain) {
    const RayBatch& b = s_.batch;
    const size_t width = size_t(b.width);
    first_ = begin;
    slotOf_.assign(end - begin, {0, 0});
    const size_t rowBegin = begin / width, rowEnd = (end + width - 1) / width;
    std::vector<uint32_t> tile;
    for (size_t y0 = rowBegin; y0 < rowEnd; y0 += kPacketSide)
      for (size_t x0 = 0; x0 < width; x0 += kPacketSide) {
        tile.clear();
        for (size_t y = y0; y < std::min(y0 + kPacketSide, rowEnd); ++y)
          for (size_t x = x0; x < std::min(x0 + kPacketSide, width); ++x) {
            const size_t e = y * width + x;
            if (e < begin || e >= end || !b.active[e]) continue;
            if (coneApex(e)) tile.push_back(uint32_t(e));
            else plain.push_back(uint32_t(e));
          }
        if (tile.empty()) continue;
        const std::optional<Cone> cone = coneOf(tile);
        if (!cone) {
          plain.insert(plain.end(), tile.begin(), tile.end());
          continue;
        }
        const uint32_t c = uint32_t(cones_.size());
        cones_.push_back(*cone);
        done_.push_back(tile.size() == 64 ? 0 : ~uint64_t(0) << tile.size());  // empty slots count as done
        members_.resize(members_.size() + 64, 0);
        for (size_t j = 0; j < tile.size(); ++j) {
          members_[size_t(c) * 64 + j] = tile[j];
          slotOf_[tile[j] - begin] = {c, uint8_t(j)};
        }
        memberCount_ += tile.size();
      }
  }

  // The apex a ray's cone would have: the eye for primary rays, the light
  // for shadow rays toward it; none for others.
  std::optional<glm::vec3> coneApex(size_t e) const {
    if (s_.frontToBack) return s_.eye;
    if (s_.batch.light && s_.batch.anyHit[e]) return *s_.batch.light;
    return std::nullopt;
  }

  // The narrowest cone about the mean direction (seen from the apex) that
  // holds every ray of the tile, widened by kConeMargin.
  std::optional<Cone> coneOf(const std::vector<uint32_t>& tile) const {
    const glm::dvec3 apex(*coneApex(tile.front()));
    std::vector<glm::dvec3> dirs;
    dirs.reserve(tile.size());
    glm::dvec3 sum(0.0);
    for (uint32_t e : tile) {
      const Ray& r = rays_[e];
      // Shadow rays run from the surface to the light: seen from the light,
      // toward their origin.
      const glm::dvec3 d = s_.frontToBack ? glm::dvec3(r.direction) : glm::dvec3(r.origin) - apex;
      const double length = glm::length(d);
      if (!(length > 0.0)) return std::nullopt;
      dirs.push_back(d / length);
      sum += dirs.back();
    }
    const double sumLength = glm::length(sum);
    if (!(sumLength > 0.0)) return std::nullopt;
    const glm::dvec3 axis = sum / sumLength;
    double widest = 0.0;
    for (const glm::dvec3& d : dirs) widest = std::max(widest, std::acos(std::clamp(glm::dot(d, axis), -1.0, 1.0)));
    widest += kConeMargin;
    if (widest > kWidestCone) return std::nullopt;
    return Cone{glm::vec3(apex), glm::vec3(axis), float(std::cos(widest))};
  }

  const Shared& s_;
  std::span<const Ray> rays_;
  FilterStats counters_;
  std::vector<uint32_t> triIds_;  // [0, triEnd): the triangles touching the current cell
  std::vector<uint32_t> rayIds_;  // [0, retired_): retired; [retired_, rayEnd): live in the current cell
  size_t retired_ = 0;            // the seed's terminatedRayPivot
  std::vector<Cone> cones_;
  std::vector<uint64_t> done_;    // per cone: a bit per ray that has its final hit
  std::vector<uint32_t> members_; // per cone: its 64 rays' elements
  std::vector<std::pair<uint32_t, uint8_t>> slotOf_;  // per element of the band: its cone and bit
  size_t first_ = 0;              // the band's first element
  size_t memberCount_ = 0;
  std::vector<uint32_t> coneIds_; // [0, conesRetired_): cones whose rays all retired
  size_t conesRetired_ = 0;       // the seed's terminatedConePivot
  int packetDepth_ = 0;
};

}  // namespace

FilterStats trace(std::span<const Triangle> tris, const Settings& settings, const RayBatch& batch,
                  std::span<Hit> hits, std::span<RayStats> stats) {
  const size_t n = batch.rays.size();
  std::vector<glm::vec3> invDir(n);
  Shared shared{tris, settings, batch, hits, stats, invDir, {}, false, {}};
  for (const Triangle& t : tris) shared.root.extend(t.bounds());
  // Front to back from one eye only when every ray really starts there.
  bool any = false;
  shared.frontToBack = batch.primary;
  for (size_t e = 0; e < n && shared.frontToBack; ++e) {
    if (!batch.active[e] || batch.anyHit[e]) continue;
    if (!any) shared.eye = batch.rays[e].origin, any = true;
    shared.frontToBack = batch.rays[e].origin == shared.eye;
  }
  for (size_t e = 0; e < n && shared.frontToBack; ++e) shared.frontToBack = !batch.active[e] || !batch.anyHit[e];

  // Task parallelism over screen bands (rows, a multiple of 8 for the
  // packets): each band runs DACRT over every triangle on its own index
  // arrays. Measured against one band per thread in docs/bench-dacrt.
  const unsigned threads = batch.threads ? batch.threads : unsigned(tbb::this_task_arena::max_concurrency());
  const size_t width = batch.width > 0 ? size_t(batch.width) : n;
  const size_t rows = width ? (n + width - 1) / width : 0;
  const size_t bands = std::max<size_t>(1, std::min<size_t>(size_t(threads) * kBandsPerThread, (rows + 7) / 8));
  const size_t rowsPerBand = ((rows + bands - 1) / bands + 7) / 8 * 8;
  if (rows <= rowsPerBand) {  // one band (a single ray from intersect): no arena to set up
    Band worker(shared);
    return worker.run(0, n);
  }
  tbb::combinable<FilterStats> counters;
  tbb::task_arena arena{int(threads)};
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rows ? (rows + rowsPerBand - 1) / rowsPerBand : 0, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t band = r.begin(); band < r.end(); ++band) {
                          const size_t begin = band * rowsPerBand * width;
                          const size_t end = std::min(n, begin + rowsPerBand * width);
                          Band worker(shared);
                          counters.local() += worker.run(begin, end);
                        }
                      },
                      tbb::simple_partitioner());
  });
  FilterStats total;
  counters.combine_each([&](const FilterStats& c) { total += c; });
  return total;
}

}  // namespace passtrace::dacrt
