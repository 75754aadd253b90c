#include "render/cpu_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include "render/camera.h"
#include "render/parallel_for.h"
#include "render/shading.h"

namespace passtrace {

CpuRenderer::CpuRenderer(const Scene& scene, const CpuAccelerator& accelerator, unsigned threads)
    : scene_(scene), accelerator_(accelerator), threads_(threads ? threads : std::thread::hardware_concurrency()) {}

// A batch tracer (DACRT) gets the whole generation at once: the rays of all
// paths still going, each with its own tMax, shadow rays marked any-hit.
uint64_t CpuRenderer::traceGeneration(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width,
                                      int height, FrameStats& frame) const {
  const size_t elements = paths.size();
  std::vector<Ray> rays(elements);
  std::vector<uint8_t> active(elements), anyHit(elements);
  std::vector<RayStats> stats(elements);
  uint64_t count = 0;
  for (size_t i = 0; i < elements; ++i) {
    rays[i] = paths[i].ray;
    active[i] = paths[i].kind != RayKind::None;
    anyHit[i] = paths[i].kind == RayKind::Shadow;
    count += active[i];
  }
  if (count == 0) return 0;
  RayBatch batch{rays, active, anyHit, width, height, primary, scene_.light.position, threads_};
  if (const std::optional<FilterStats> filter = accelerator_.traceBatch(batch, hits, stats))
    frame.filter = frame.filter.value_or(FilterStats{}) += *filter;
  for (size_t i = 0; i < elements; ++i) {
    paths[i].steps += stats[i].steps;
    paths[i].triangleTests += stats[i].triangleTests;
  }
  return count;
}

FrameResult CpuRenderer::render(const CameraSpec& camera, int width, int height, int bounces, bool captureHits) {
  const CameraBasis basis = makeCameraBasis(camera, width, height);
  const size_t elements = size_t(width) * size_t(height);
  const float epsilon = secondaryRayEpsilon(scene_);
  constexpr size_t kGrain = 256;  // pixels per work item: about one image row

  FrameResult result;
  result.width = width;
  result.height = height;
  std::vector<PathState> paths(elements);
  std::vector<Hit> hits(elements);
  const auto start = std::chrono::steady_clock::now();
  std::chrono::steady_clock::duration excluded{};

  parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      paths[i].ray = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));
  });

  for (int bounce = 1; bounce <= bounces; ++bounce) {
    std::atomic<uint64_t> active{0};
    if (accelerator_.tracesBatches()) {
      active = traceGeneration(paths, hits, bounce == 1, width, height, result.stats);
    } else
    parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
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
    if (active == 0) break;
    result.stats.rays += active;
    ++result.stats.passes;

    if (bounce == 1 && captureHits) {
      const auto pause = std::chrono::steady_clock::now();
      result.primaryHits.reserve(elements);
      for (const Hit& h : hits) result.primaryHits.push_back(hitRecordOf(h));
      excluded += std::chrono::steady_clock::now() - pause;
    }

    const bool last = bounce == bounces;
    parallelFor(elements, kGrain, threads_, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) shadeElement(scene_, epsilon, last, hits[i], paths[i]);
    });
  }
  result.stats.frameMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start - excluded).count();

  result.rgb.reserve(3 * elements);
  result.steps.reserve(elements);
  for (const PathState& p : paths) {
    result.steps.push_back(float(p.steps));
    result.rgb.insert(result.rgb.end(), {p.color.r, p.color.g, p.color.b});
    result.stats.steps += p.steps;
    result.stats.triangleTests += p.triangleTests;
    result.stats.maxStepsPerRay = std::max<uint64_t>(result.stats.maxStepsPerRay, p.steps);
    result.stats.maxTriangleTestsPerRay = std::max<uint64_t>(result.stats.maxTriangleTestsPerRay, p.triangleTests);
  }
  return result;
}

}  // namespace passtrace
