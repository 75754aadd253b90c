#include "render/ray_query.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "render/parallel_for.h"

namespace passtrace {

void traceRays(const CpuAccelerator& structure, std::span<const Ray> rays, bool anyHit, std::span<Hit> hits,
               std::span<RayStats> stats, unsigned threads) {
  if (hits.size() != rays.size() || (!stats.empty() && stats.size() != rays.size()))
    throw std::invalid_argument("traceRays: hits and stats need one entry per ray");
  std::fill(hits.begin(), hits.end(), Hit{});
  std::fill(stats.begin(), stats.end(), RayStats{});
  if (rays.empty()) return;

  if (structure.packetSize() == 0 && structure.tracesBatches()) {
    // DACRT: all rays at once, as one generation of the renderer's.
    const std::vector<uint8_t> active(rays.size(), 1), anyHits(rays.size(), anyHit ? 1 : 0);
    std::vector<RayStats> local(stats.empty() ? rays.size() : 0);
    RayBatch batch;
    batch.rays = rays;
    batch.active = active;
    batch.anyHit = anyHits;
    batch.threads = threads;
    structure.traceBatch(batch, hits, stats.empty() ? std::span<RayStats>(local) : stats);
    return;
  }

  const size_t packet = structure.packetSize() > 0 ? size_t(RayPacket::kMax) : 1;
  // Chunks of 256 rays (whole packets): small enough to balance rays of very
  // different cost over the threads, large enough to amortise the stealing.
  const size_t grain = std::max<size_t>(packet, 256);
  parallelFor(rays.size(), grain, threads, [&](size_t begin, size_t end) {
    RayStats scratch[RayPacket::kMax];
    for (size_t i = begin; i < end; i += packet) {
      const size_t n = std::min(packet, end - i);
      if (packet == 1) {
        hits[i] = structure.intersect(rays[i], anyHit, stats.empty() ? nullptr : &stats[i]);
        continue;
      }
      const RayPacket p = RayPacket::of(rays.subspan(i, n));
      std::span<RayStats> packetStats = stats.subspan(i, n);
      if (stats.empty()) {  // the tracer adds to them
        packetStats = std::span<RayStats>(scratch, n);
        std::fill(packetStats.begin(), packetStats.end(), RayStats{});
      }
      structure.tracePacket(p, anyHit, hits.subspan(i, n), packetStats);
    }
  });
}

}  // namespace passtrace
