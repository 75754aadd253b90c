// The baseline a user would compare passtrace's -r 3 with: the CPU renderer's
// primary rays (render/camera.h, the scene's own camera) traced by a bare
// rtcIntersect1 loop over oneTBB threads, no shading and no frame buffer.
// Prints one JSON line; Mrays/s is rays over the minimum time of the repeats.
//
//   build/tests/measure/measure_bare_embree SCENE [WIDTH=512] [THREADS=2] [REPEATS=5]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "render/camera.h"
#include "scenes/scene_registry.h"

namespace {

using namespace passtrace;

RTCScene buildScene(RTCDevice device, const Scene& scene) {
  RTCScene rtc = rtcNewScene(device);
  rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_HIGH);  // as accel/embree/ builds it
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = scene.triangles.size();
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 p[3] = {scene.triangles[i].v0, scene.triangles[i].v1, scene.triangles[i].v2};
    for (size_t k = 0; k < 3; ++k) {
      v[9 * i + 3 * k] = p[k].x, v[9 * i + 3 * k + 1] = p[k].y, v[9 * i + 3 * k + 2] = p[k].z;
      idx[3 * i + k] = unsigned(3 * i + k);
    }
  }
  rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(rtc, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(rtc);
  return rtc;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [WIDTH=512] [THREADS=2] [REPEATS=5]\n", argv[0]);
    return 2;
  }
  const std::string sceneName = argv[1];
  const int width = argc > 2 ? std::stoi(argv[2]) : 512;
  const int threads = argc > 3 ? std::stoi(argv[3]) : 2;
  const int repeats = argc > 4 ? std::stoi(argv[4]) : 5;
  if (width <= 0 || threads <= 0 || repeats <= 0) throw std::invalid_argument("WIDTH, THREADS, REPEATS must be > 0");

  const Scene scene = loadScene(sceneName);
  const CameraBasis basis = makeCameraBasis(scene.camera, width, width);
  const size_t count = size_t(width) * size_t(width);
  std::vector<Ray> rays(count);
  for (size_t i = 0; i < count; ++i) rays[i] = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));

  RTCDevice device = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
  RTCScene rtc = buildScene(device, scene);
  std::vector<unsigned> primIds(count);
  tbb::task_arena arena(threads);
  double best = std::numeric_limits<double>::infinity();
  size_t hits = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 256), [&](const tbb::blocked_range<size_t>& range) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t i = range.begin(); i < range.end(); ++i) {
          RTCRayHit rh{};
          const Ray& ray = rays[i];
          rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
          rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
          rh.ray.tnear = 0.0f, rh.ray.tfar = ray.tMax, rh.ray.mask = ~0u;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(rtc, &context, &rh);
          primIds[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? ~0u : rh.hit.primID;
        }
      });
    });
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  for (unsigned id : primIds) hits += id != ~0u;
  std::printf("{\"scene\": \"%s\", \"width\": %d, \"threads\": %d, \"repeats\": %d, \"rays\": %zu, \"hits\": %zu, "
              "\"min_ms\": %.3f, \"mrays_per_s\": %.3f}\n",
              sceneName.c_str(), width, threads, repeats, count, hits, best, double(count) / best / 1000.0);
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "measure_bare_embree: %s\n", e.what());
  return 1;
}
