#include "render/cone_tracer.h"

#include <chrono>

#include <tbb/enumerable_thread_specific.h>

#include "render/parallel_for.h"

namespace passtrace {

ConeFrame traceCones(const ConeTraversal& traversal, const CameraBasis& camera, float halfAngle,
                     const ConeQueryConfig& config, unsigned threads) {
  ConeFrame frame;
  frame.width = camera.width, frame.height = camera.height;
  const size_t pixels = size_t(camera.width) * size_t(camera.height);
  frame.hits.resize(pixels);
  frame.nodes.resize(pixels);
  frame.triangles.resize(pixels);
  struct Local {
    ConeScratch scratch;
    ConeResult result;
  };
  tbb::enumerable_thread_specific<Local> locals;
  const auto start = std::chrono::steady_clock::now();
  parallelFor(size_t(camera.height), 1, threads, [&](size_t y0, size_t y1) {
    Local& local = locals.local();
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const Ray ray = primaryRay(camera, x, int(y));
        const Cone cone{ray.origin, ray.direction, halfAngle};
        traversal.query(cone, config, local.scratch, local.result);
        const size_t i = y * size_t(camera.width) + size_t(x);
        const ConeResult& r = local.result;
        frame.hits[i] = r.hits.empty() ? ConeHitRecord{0, kNoHit, kInfinity}
                                       : ConeHitRecord{r.count(), r.hits.front().id, r.hits.front().t};
        frame.nodes[i] = r.nodes;
        frame.triangles[i] = r.triangleTests;
      }
  });
  frame.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

}  // namespace passtrace
