#include "accel/wide_bvh/wide_bvh_structure.h"

#include <algorithm>
#include <chrono>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/sbvh_binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"

namespace passtrace {
namespace {

class Bvh8Accelerator final : public CpuAccelerator {
public:
  Bvh8Accelerator(std::span<const Triangle> tris, const AccelBuildConfig& config, bool packets)
      : tris_(tris), test_(config.triangleTest) {
    const TriangleTest test = config.triangleTest;
    const auto start = std::chrono::steady_clock::now();
    const SahBuildConfig sah;
    const SahBinaryBvh binary = config.bvh8Builder == Bvh8BuilderKind::Sbvh ? buildSbvhBinaryBvh(tris, sah)
                                                                             : buildBinnedSahBvh(tris, sah);
    bvh_ = collapseToWideBvh(binary, tris);
    stats_.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats_.name = packets ? "bvh8-packet" : "bvh8";
    stats_.nodes = bvh_.nodes.size() + bvh_.leaves;
    stats_.leaves = bvh_.leaves;
    stats_.references = bvh_.references;
    stats_.depth = bvh_.depth;
    stats_.sahCost = bvhSahCost(binary, sah);
    stats_.structureBytes = bvh_.nodes.size() * sizeof(WideBvhNode) + bvh_.packs.size() * sizeof(TrianglePack);
    stats_.nodeTestBytes = sizeof(WideBvhNode);  // a node test is a visit: eight boxes and their links
    stats_.triangleTestBytes = sizeof(TrianglePack) / kTrianglePackWidth;
    // Node floats only (the packs are the triangles): 6 x 8 bounds + 8 child references.
    stats_.floatsPerTriangle = tris.empty() ? 0.0 : double(bvh_.nodes.size()) * 56.0 / double(tris.size());
    traverse_ = wideBvhAvx2Available() ? traverseWideBvhAvx2 : traverseWideBvhScalar;
    // Packets need AVX2 and the Möller–Trumbore pack test; otherwise the renderer's per-ray loop.
    packets_ = packets && wideBvhAvx2Available() && test == TriangleTest::MollerTrumbore;
    takeTurns_ = bvh_.bytes() > kTakeTurnsAboveBytes;
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverse_(bvh_, tris_, ray, anyHit, test_, stats);
  }
  bool tracesBatches() const override { return packets_; }
  std::optional<FilterStats> traceBatch(const RayBatch& batch, std::span<Hit> hits,
                                        std::span<RayStats> stats) const override;
  int packetSize() const override { return packets_ ? kWidePacketMax : 0; }
  void tracePacket(const RayPacket& rays, bool anyHit, std::span<Hit> hits,
                   std::span<RayStats> stats) const override {
    traceWideBvhPacketAvx2(bvh_, rays, anyHit, hits, stats, packetConfigFor(anyHit));
  }
  // Packets take turns over a tree that does not fit the caches (kTakeTurnsAboveBytes); eight at once
  // keep four walking (kPacketsInFlight) as walks end.
  int packetsAtOnce() const override { return takeTurns_ ? 8 : 1; }
  void tracePackets(std::span<const PacketJob> jobs, bool anyHit) const override {
    traceWideBvhPacketsAvx2(bvh_, jobs, anyHit, packetConfigFor(anyHit), takeTurns_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  using Traverse = Hit (*)(const WideBvh&, std::span<const Triangle>, const Ray&, bool, TriangleTest, RayStats*);
  std::span<const Triangle> tris_;
  TriangleTest test_;
  WideBvh bvh_;
  AccelStats stats_;
  Traverse traverse_ = nullptr;
  bool packets_ = false;
  bool takeTurns_ = false;
};

// Packets of 32 neighbouring elements: 8x4 pixel tiles when the batch has an
// image layout, else runs of 32 (CPU time per frame, one thread, against
// 4x2 and 4x4 tiles: 8x4 was fastest on bunny, Kitchen and Robots). Primary
// and shadow rays go as packets (coherent: a common origin, or a common end at
// the light); other rays (reflections) one at a time, where packets would
// mostly carry dead lanes.
std::optional<FilterStats> Bvh8Accelerator::traceBatch(const RayBatch& batch, std::span<Hit> hits,
                                                       std::span<RayStats> stats) const {
  constexpr int kTileW = 8, kTileH = 4, kTile = kTileW * kTileH;
  const size_t n = batch.rays.size();
  const bool image = batch.width > 0 && size_t(batch.width) * size_t(batch.height) == n;
  const size_t tilesX = image ? (size_t(batch.width) + kTileW - 1) / kTileW : 0;
  const size_t tiles = image ? tilesX * ((size_t(batch.height) + kTileH - 1) / kTileH) : (n + kTile - 1) / kTile;
  auto traceTiles = [&](size_t begin, size_t end) {
    RayPacket rays;  // one per work item: RayPacket clears its arrays when made
    for (size_t tile = begin; tile < end; ++tile) {
      size_t index[kTile];
      int count = 0;
      if (image) {
        const size_t x0 = (tile % tilesX) * kTileW, y0 = (tile / tilesX) * kTileH;
        for (size_t y = y0; y < std::min(y0 + kTileH, size_t(batch.height)); ++y)
          for (size_t x = x0; x < std::min(x0 + kTileW, size_t(batch.width)); ++x)
            index[count++] = y * size_t(batch.width) + x;
      } else {
        for (size_t i = tile * kTile; i < std::min(tile * kTile + kTile, n); ++i) index[count++] = i;
      }
      // One pass sorts the tile's rays into the two packets (closest hit, shadow).
      size_t members[2][kTile];
      int sizes[2] = {0, 0};
      for (int k = 0; k < count; ++k) {
        const size_t i = index[k];
        if (!batch.active[i]) continue;
        const int shadow = batch.anyHit[i] != 0;
        if (!shadow && !batch.primary) {
          hits[i] = intersect(batch.rays[i], false, &stats[i]);
          continue;
        }
        members[shadow][sizes[shadow]++] = i;
      }
      for (int shadow = 0; shadow < 2; ++shadow) {
        const int m = sizes[shadow];
        if (m == 0) continue;
        Hit packetHits[kTile];
        RayStats packetStats[kTile];
        rays.count = 0;
        for (int k = 0; k < m; ++k) rays.push(batch.rays[members[shadow][k]]);
        traceWideBvhPacketAvx2(bvh_, rays, shadow != 0, std::span<Hit>(packetHits, size_t(m)),
                               std::span<RayStats>(packetStats, size_t(m)), packetConfigFor(shadow != 0));
        for (int k = 0; k < m; ++k) {
          const size_t i = members[shadow][k];
          hits[i] = packetHits[k];
          stats[i].steps += packetStats[k].steps;
          stats[i].triangleTests += packetStats[k].triangleTests;
        }
      }
    }
  };
  tbb::task_arena arena(batch.threads ? int(batch.threads) : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles, std::max<size_t>(1, 256 / kTile)),
                      [&](const tbb::blocked_range<size_t>& r) { traceTiles(r.begin(), r.end()); },
                      tbb::simple_partitioner());
  });
  return std::nullopt;
}

}  // namespace

std::unique_ptr<CpuAccelerator> makeBvh8Cpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<Bvh8Accelerator>(tris, config, false);
}

std::unique_ptr<CpuAccelerator> makeBvh8PacketCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  return std::make_unique<Bvh8Accelerator>(tris, config, true);
}

}  // namespace passtrace
