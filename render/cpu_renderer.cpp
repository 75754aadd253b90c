#include "render/cpu_renderer.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <mutex>

#include "render/camera.h"
#include "render/parallel_for.h"
#include "render/shading.h"

namespace passtrace {
namespace {

// The most tiles whose packets go to the tracer together
// (CpuAccelerator::packetsAtOnce, tracePackets), so that it may interleave
// them: one packet's cache misses then overlap the others' work (bvh8-packet
// over large trees: docs/bench-speed/NOTES.md).
constexpr size_t kTileGroup = 8;

// An image cut into tiles of tileW x tileH pixels, numbered row by row; the
// last column and row of tiles may be cut short by the image's edge.
struct TileGrid {
  struct Tile {
    size_t x0, y0, columns, rows;  // the first pixel, and the pixels across and down
  };
  size_t tileW, tileH, width, height, tilesX, tilesY;
  TileGrid(size_t tileW, size_t tileH, int width, int height)
      : tileW(tileW), tileH(tileH), width(size_t(width)), height(size_t(height)),
        tilesX((size_t(width) + tileW - 1) / tileW), tilesY((size_t(height) + tileH - 1) / tileH) {}
  size_t count() const { return tilesX * tilesY; }
  Tile operator[](size_t tile) const {
    const size_t x0 = (tile % tilesX) * tileW, y0 = (tile / tilesX) * tileH;
    return {x0, y0, std::min(tileW, width - x0), std::min(tileH, height - y0)};
  }
};

// Adds pixels' step and triangle-test sums to a frame's, and takes the larger maxima.
void addPixelCounts(FrameStats& into, const FrameStats& counts) {
  into.steps += counts.steps;
  into.triangleTests += counts.triangleTests;
  into.maxStepsPerRay = std::max(into.maxStepsPerRay, counts.maxStepsPerRay);
  into.maxTriangleTestsPerRay = std::max(into.maxTriangleTestsPerRay, counts.maxTriangleTestsPerRay);
}

// A finished pixel into the image: its colour, its steps (the heat map's
// value) and its counts into `counts`, the caller's share of the frame's.
// Packet rows write each tile's pixels as they finish, per-ray rows the whole
// frame at the end; this is the one place that says what a pixel leaves.
void writePixel(FrameResult& image, size_t pixel, const glm::vec3& color, uint64_t steps, uint64_t triangleTests,
                FrameStats& counts) {
  float* rgb = image.rgb.data() + 3 * pixel;  // not copy_n: that called memmove per pixel
  rgb[0] = color.r, rgb[1] = color.g, rgb[2] = color.b;
  image.steps[pixel] = float(steps);
  counts.steps += steps;
  counts.triangleTests += triangleTests;
  counts.maxStepsPerRay = std::max(counts.maxStepsPerRay, steps);
  counts.maxTriangleTestsPerRay = std::max(counts.maxTriangleTestsPerRay, triangleTests);
}

}  // namespace

CpuRenderer::CpuRenderer(const Scene& scene, const CpuAccelerator& accelerator, unsigned threads,
                         ShadingConfig shading)
    : scene_(scene),
      accelerator_(accelerator),
      // oneTBB's count follows the process's CPU affinity (mpirun binds
      // each rank to its cores); hardware_concurrency() counts the machine's.
      threads_(threads ? threads : unsigned(tbb::this_task_arena::max_concurrency())),
      shading_(shading),
      table_(makeShadingTable(scene, threads_)),
      epsilon_(secondaryRayEpsilon(scene)),
      aoLength_(aoDistance(scene, shading)) {}

void CpuRenderer::prefetchShading(const Hit& hit) const {
  if (hit.id >= table_.size()) return;
  __builtin_prefetch(&table_[hit.id]);
  if (scene_.hasVertexNormals()) __builtin_prefetch(&scene_.vertexNormals[hit.id]);
}

void CpuRenderer::shade(const Generation& g, size_t i, const Hit& hit, PathState& path) const {
  if (shading_.mode == ShadingMode::Thesis)
    shadeElement(scene_, g.epsilon, g.last, hit, path, table_);
  else if (shading_.mode == ShadingMode::Whitted)
    shadeWhitted(scene_, g.epsilon, g.bounces, hit, path, (*g.stacks)[i], table_);
  else
    shadeAo(scene_, g.epsilon, shading_.aoSamples, g.aoLength, uint32_t(g.rows->globalPixel(i, g.width)), hit, path,
            table_);
}

// A batch tracer (DACRT) gets the whole generation at once: the rays of all
// paths still going, each with its own tMax, shadow rays marked any-hit. The
// copies in and out run on all threads into arrays kept for the frame: done
// serially they cost about 13 % of a bunny primary frame with bvh8-packet.
uint64_t CpuRenderer::traceGeneration(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width,
                                      int height, FrameStats& frame, BatchScratch& scratch) const {
  constexpr size_t kGrain = 4096;  // elements per work item: plain copies
  const size_t elements = paths.size();
  scratch.rays.resize(elements);
  scratch.active.resize(elements);
  scratch.anyHit.resize(elements);
  scratch.stats.resize(elements);
  std::atomic<uint64_t> count{0};
  parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
    uint64_t local = 0;
    for (size_t i = begin; i < end; ++i) {
      scratch.rays[i] = paths[i].ray;
      scratch.active[i] = paths[i].kind != RayKind::None;
      scratch.anyHit[i] = paths[i].kind == RayKind::Shadow;
      scratch.stats[i] = RayStats{};
      local += scratch.active[i];
    }
    count += local;
  });
  if (count == 0) return 0;
  RayBatch batch{scratch.rays, scratch.active, scratch.anyHit, width, height, primary, scene_.light.position, threads_};
  if (const std::optional<FilterStats> filter = accelerator_.traceBatch(batch, hits, scratch.stats))
    frame.filter = frame.filter.value_or(FilterStats{}) += *filter;
  parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      paths[i].steps += scratch.stats[i].steps;
      paths[i].triangleTests += scratch.stats[i].triangleTests;
    }
  });
  return count;
}

// Packet rows, frames of two or more generations: each group of 8x8 tiles is
// traced generation after generation to its end before the next group, its
// paths kept in the thread's scratch (under 60 KB, in the L2 cache) instead of
// a frame-wide array of 112-byte path states, which every generation walked
// again from memory (29 MB at 512²; with shadow rays on the bunny the renderer
// around the traversal then took more samples than the traversal itself:
// docs/bench-speed/NOTES.md). Each pixel's rays, shading and counts are the
// same as generation by generation over the whole frame, so are its bits.
// Primary rays go as two 8x4 packets per tile (the fastest of 4x2, 4x4 and
// 8x4 on bunny, Kitchen and Robots; a common origin); shadow and AO rays as
// one packet of up to 64 per tile (a common end at the light; against 16 and
// 32 per packet, 64 took the least CPU time on Robots); mirror rays one at a
// time, where packets would mostly carry dead lanes.
CpuRenderer::Traced CpuRenderer::traceTileGroups(const CameraBasis& basis, int width, int height, int generations,
                                                 int bounces, bool captureHits, const RowBands& rows,
                                                 std::vector<WhittedStack>& stacks, std::vector<Hit>& hits,
                                                 FrameResult& pixels) const {
  constexpr size_t kTileW = 8, kTileH = 8, kTile = kTileW * kTileH, kHalfRows = kTileH / 2;
  static_assert(kTile <= size_t(RayPacket::kMax), "a tile's shadow rays are one packet");
  const TileGrid grid(kTileW, kTileH, width, height);
  std::atomic<uint64_t> rays{0};
  std::atomic<int> passes{0};
  std::mutex statsLock;
  const size_t tileGroup = std::clamp<size_t>(size_t(accelerator_.packetsAtOnce()), 1, kTileGroup);
  parallelFor(grid.count(), std::max<size_t>(tileGroup, 256 / kTile), threads_, [&](size_t begin, size_t end) {
    // Per tile of the group: its paths and their pixels row by row and hits;
    // per packet (two per tile for primary rays, one later) its rays, the
    // tile's paths it carries, its hits and counts. The thread's own, made
    // once: made per work item, scratch like this cost 10 % of a bunny frame.
    struct Scratch {
      PathState paths[kTileGroup][kTile];
      Hit tileHits[kTileGroup][kTile];
      size_t pixel[kTileGroup][kTile];
      size_t pixels[kTileGroup];
      RayPacket packets[2 * kTileGroup];
      uint8_t members[2 * kTileGroup][kTile];
      Hit packetHits[2 * kTileGroup][kTile];
      RayStats packetStats[2 * kTileGroup][kTile];
      PacketJob jobs[2 * kTileGroup];
    };
    thread_local Scratch scratch;
    auto& [paths, tileHits, pixel, pixelCount, packets, members, packetHits, packetStats, jobs] = scratch;
    FrameStats counts;  // this work item's share of the frame's sums and maxima
    uint64_t traced = 0;
    int deepest = 0;
    for (size_t first = begin; first < end; first += tileGroup) {
      const size_t group = std::min(tileGroup, end - first);
      for (int bounce = 1; bounce <= generations; ++bounce) {
        const bool primary = bounce == 1;
        const Generation g{primary ? &basis : nullptr, width, epsilon_, bounce == bounces, bounces, aoLength_,
                           &stacks, primary && captureHits, &rows};
        const size_t packetSlots = primary ? 2 * group : group;
        for (size_t s = 0; s < packetSlots; ++s) packets[s].count = 0;
        uint64_t active = 0;
        for (size_t t = 0; t < group; ++t) {
          if (primary) {  // the tile's paths start: camera rays, row by row
            const auto [x0, y0, columns, tileRows] = grid[first + t];
            float screenX[kTileW] = {}, dirX[kTileW], dirY[kTileW], dirZ[kTileW];
            for (size_t x = 0; x < columns; ++x) screenX[x] = cameraScreenX(basis, int(x0 + x));
            size_t n = 0;
            for (size_t y = 0; y < tileRows; ++y) {
              cameraDirections(basis, screenX, cameraScreenY(basis, int(y0 + y)), dirX, dirY, dirZ);
              RayPacket& packet = packets[2 * t + (y >= kHalfRows)];
              for (size_t x = 0; x < columns; ++x, ++n) {
                pixel[t][n] = (y0 + y) * size_t(width) + x0 + x;
                PathState& path = paths[t][n];
                path = PathState{};
                path.ray = Ray{basis.eye, glm::vec3(dirX[x], dirY[x], dirZ[x]), kInfinity};
                members[2 * t + (y >= kHalfRows)][packet.count] = uint8_t(n);
                packet.push(path.ray);
              }
            }
            pixelCount[t] = n;
            active += n;
            continue;
          }
          for (size_t j = 0; j < pixelCount[t]; ++j) {
            PathState& path = paths[t][j];
            if (path.kind == RayKind::None) continue;
            ++active;
            if (path.kind != RayKind::Shadow) {  // a mirror or refraction ray: alone
              RayStats stats;
              tileHits[t][j] = accelerator_.intersect(path.ray, false, &stats);
              path.steps += stats.steps;
              path.triangleTests += stats.triangleTests;
              continue;
            }
            members[t][packets[t].count] = uint8_t(j);
            packets[t].push(path.ray);
          }
        }
        if (active == 0) break;  // shading paths without rays would change nothing
        traced += active;
        deepest = std::max(deepest, bounce);
        size_t jobCount = 0;
        for (size_t s = 0; s < packetSlots; ++s) {
          const size_t m = size_t(packets[s].count);
          if (m == 0) continue;
          std::fill_n(packetStats[s], m, RayStats{});
          jobs[jobCount++] = PacketJob{&packets[s], packetHits[s], packetStats[s]};
        }
        if (jobCount > 0) accelerator_.tracePackets(std::span<const PacketJob>(jobs, jobCount), !primary);
        for (size_t s = 0; s < packetSlots; ++s) {
          const size_t t = primary ? s / 2 : s;
          for (size_t k = 0; k < size_t(packets[s].count); ++k) {
            const uint8_t j = members[s][k];
            tileHits[t][j] = packetHits[s][k];
            paths[t][j].steps += packetStats[s][k].steps;
            paths[t][j].triangleTests += packetStats[s][k].triangleTests;
          }
        }
        // The hit triangles' shading data is fetched for a whole tile first,
        // so that its cache misses overlap instead of stalling one pixel at a time.
        for (size_t t = 0; t < group; ++t) {
          for (size_t j = 0; j < pixelCount[t]; ++j) prefetchShading(tileHits[t][j]);
          for (size_t j = 0; j < pixelCount[t]; ++j) {
            shade(g, pixel[t][j], tileHits[t][j], paths[t][j]);
            if (g.keepHits) hits[pixel[t][j]] = tileHits[t][j];
          }
        }
      }
      for (size_t t = 0; t < group; ++t)
        for (size_t j = 0; j < pixelCount[t]; ++j) {
          const PathState& path = paths[t][j];
          writePixel(pixels, pixel[t][j], path.color, path.steps, path.triangleTests, counts);
        }
    }
    rays += traced;
    for (int seen = passes.load(); seen < deepest && !passes.compare_exchange_weak(seen, deepest);) {
    }
    const std::lock_guard<std::mutex> hold(statsLock);
    addPixelCounts(pixels.stats, counts);
  });
  return Traced{rays.load(), passes.load()};
}

// The speed runs' frame, primary rays only with the thesis's shading (-b 1):
// every path ends at its first hit, so no path state is kept at all. Each
// 8x4 tile's rays go from the camera into one packet, eight directions per
// row at once, and the packet's hits straight to pixels (shadePrimaryOnly),
// instead of a 112-byte path state per pixel written, copied into the
// packet and read back.
uint64_t CpuRenderer::tracePrimaryOnly(const CameraBasis& basis, int width, int height, std::vector<Hit>* hits,
                                       FrameResult& pixels) const {
  constexpr size_t kTileW = 8, kTileH = 4, kTile = kTileW * kTileH;
  static_assert(kTile <= size_t(RayPacket::kMax), "a tile's rays are one packet");
  const TileGrid grid(kTileW, kTileH, width, height);
  std::mutex statsLock;
  const size_t tileGroup = std::clamp<size_t>(size_t(accelerator_.packetsAtOnce()), 1, kTileGroup);
  parallelFor(grid.count(), std::max<size_t>(tileGroup, 256 / kTile), threads_, [&](size_t begin, size_t end) {
    FrameStats counts;  // this work item's share of the frame's sums and maxima
    struct Scratch {  // the thread's own, made once (as tracePackets')
      RayPacket packets[kTileGroup];
      Hit packetHits[kTileGroup][kTile];
      RayStats packetStats[kTileGroup][kTile];
      PacketJob jobs[kTileGroup];
    };
    thread_local Scratch scratch;
    auto& [packets, packetHits, packetStats, jobs] = scratch;
    for (size_t first = begin; first < end; first += tileGroup) {
      const size_t group = std::min(tileGroup, end - first);
      for (size_t g = 0; g < group; ++g) {
        RayPacket& packet = packets[g];
        const auto [x0, y0, columns, rows] = grid[first + g];
        float screenX[kTileW] = {}, dirX[kTileW], dirY[kTileW], dirZ[kTileW];
        for (size_t x = 0; x < columns; ++x) screenX[x] = cameraScreenX(basis, int(x0 + x));
        packet.count = int(rows * columns);
        for (size_t y = 0; y < rows; ++y) {  // packet lanes row by row, as tracePackets orders them
          cameraDirections(basis, screenX, cameraScreenY(basis, int(y0 + y)), dirX, dirY, dirZ);
          std::fill_n(packet.ox + y * columns, columns, basis.eye.x);
          std::fill_n(packet.oy + y * columns, columns, basis.eye.y);
          std::fill_n(packet.oz + y * columns, columns, basis.eye.z);
          std::copy_n(dirX, columns, packet.dx + y * columns);
          std::copy_n(dirY, columns, packet.dy + y * columns);
          std::copy_n(dirZ, columns, packet.dz + y * columns);
          std::fill_n(packet.tMax + y * columns, columns, kInfinity);
        }
        std::fill_n(packetStats[g], size_t(packet.count), RayStats{});
        jobs[g] = PacketJob{&packet, packetHits[g], packetStats[g]};
      }
      accelerator_.tracePackets(std::span<const PacketJob>(jobs, group), false);
      for (size_t g = 0; g < group; ++g) {
        const RayPacket& packet = packets[g];
        const auto [x0, y0, columns, rows] = grid[first + g];
        const size_t n = size_t(packet.count);
        for (size_t k = 0; k < n; ++k) prefetchShading(packetHits[g][k]);  // their misses overlap
        for (size_t y = 0, k = 0; y < rows; ++y)
          for (size_t x = 0; x < columns; ++x, ++k) {
            const size_t pixel = (y0 + y) * size_t(width) + x0 + x;
            const Hit& hit = packetHits[g][k];
            const glm::vec3 color = shadePrimaryOnly(scene_, epsilon_, packet.ray(int(k)), hit, table_);
            const RayStats& stats = packetStats[g][k];
            writePixel(pixels, pixel, color, stats.steps, stats.triangleTests, counts);
            if (hits) (*hits)[pixel] = hit;
          }
      }
    }
    const std::lock_guard<std::mutex> hold(statsLock);
    addPixelCounts(pixels.stats, counts);
  });
  return uint64_t(width) * uint64_t(height);
}

uint64_t CpuRenderer::traceRays(std::vector<PathState>& paths, std::vector<Hit>& hits) const {
  constexpr size_t kGrain = 256;  // pixels per work item: about one image row
  std::atomic<uint64_t> active{0};
  parallelFor(paths.size(), kGrain, threads_, [&](size_t begin, size_t end) {
    uint64_t count = 0;
    for (size_t i = begin; i < end; ++i) {
      PathState& path = paths[i];
      if (path.kind == RayKind::None) continue;
      RayStats stats;
      hits[i] = accelerator_.intersect(path.ray, path.kind == RayKind::Shadow, &stats);
      path.steps += stats.steps;
      path.triangleTests += stats.triangleTests;
      ++count;
    }
    active += count;
  });
  return active;
}

FrameResult CpuRenderer::render(const CameraSpec& camera, int width, int height, int bounces, bool captureHits,
                                const RowBands& rows) {
  const CameraBasis basis = makeCameraBasis(camera, width, height, rows);
  const size_t elements = size_t(width) * size_t(height);
  constexpr size_t kGrain = 256;  // pixels per work item: about one image row

  FrameResult result;
  result.width = width;
  result.height = height;
  // Whitted and AO trace until no pixel has a ray left: -b bounds the ray
  // tree's depth (whitted) or is not read (ao), not the generations.
  const bool thesis = shading_.mode == ShadingMode::Thesis;
  const int generations = thesis ? bounces : std::numeric_limits<int>::max();
  const bool packets = accelerator_.packetSize() > 0, batch = !packets && accelerator_.tracesBatches();
  std::vector<Hit> hits(packets && !captureHits ? 0 : elements);  // packet rows keep hits in the tile
  std::vector<WhittedStack> stacks(shading_.mode == ShadingMode::Whitted ? elements : 0);
  const auto frameMs = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  const auto keepPrimaryHits = [&] {
    result.primaryHits.reserve(elements);
    for (const Hit& h : hits) result.primaryHits.push_back(hitRecordOf(h));
  };

  // Packet rows generate, trace and shade a group of tiles at a time and
  // write its pixels straight out: no frame-wide path state at all.
  if (packets) {
    result.rgb.assign(3 * elements, 0.0f), result.steps.assign(elements, 0.0f);
    const auto start = std::chrono::steady_clock::now();
    const Traced traced =
        generations == 1
            ? Traced{tracePrimaryOnly(basis, width, height, captureHits ? &hits : nullptr, result), 1}
            : traceTileGroups(basis, width, height, generations, bounces, captureHits, rows, stacks, hits, result);
    result.stats.frameMs = frameMs(start);
    result.stats.rays = traced.rays;
    result.stats.passes = uint64_t(traced.passes);
    if (captureHits) keepPrimaryHits();
    return result;
  }

  // The batch path traces a whole generation at once, so it generates and
  // shades in passes of their own; so do per-ray rows: in one pass, shading
  // between traversals made bvh8 3 % slower than main (why: not measured);
  // apart, 1.03-1.05x faster.
  std::vector<PathState> paths(elements);
  BatchScratch scratch;
  const auto start = std::chrono::steady_clock::now();
  std::chrono::steady_clock::duration excluded{};
  parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) paths[i].ray = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));
  });

  for (int bounce = 1; bounce <= generations; ++bounce) {
    const Generation g{nullptr, width, epsilon_, bounce == bounces, bounces, aoLength_, &stacks,
                       bounce == 1 && captureHits, &rows};
    // Shading an element without a ray changes nothing (shadeWhitted pops a
    // pending ray only when it has one), so a generation that traced nothing
    // was shaded for nothing and the loop ends as before.
    const uint64_t active =
        batch ? traceGeneration(paths, hits, bounce == 1, width, height, result.stats, scratch) : traceRays(paths, hits);
    if (active == 0) break;
    result.stats.rays += active;
    ++result.stats.passes;

    if (bounce == 1 && captureHits) {
      const auto pause = std::chrono::steady_clock::now();
      keepPrimaryHits();
      excluded += std::chrono::steady_clock::now() - pause;
    }
    parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) shade(g, i, hits[i], paths[i]);
    });
  }
  result.stats.frameMs = frameMs(start) - std::chrono::duration<double, std::milli>(excluded).count();

  result.rgb.resize(3 * elements);
  result.steps.resize(elements);
  for (size_t i = 0; i < elements; ++i)
    writePixel(result, i, paths[i].color, paths[i].steps, paths[i].triangleTests, result.stats);
  return result;
}

}  // namespace passtrace
