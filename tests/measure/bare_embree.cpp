// The baseline a user would compare passtrace's -r 3 with: the CPU renderer's
// primary rays (render/camera.h, the scene's own camera) traced by a bare
// rtcIntersect1 loop over oneTBB threads, no shading and no frame buffer.
// Prints one JSON line; Mrays/s is rays over the minimum time of the repeats.
// --packet traces the same rays as rtcIntersect16 (8 without AVX-512) packets
// of 8x2 (8x1) pixel tiles instead, the baseline of -r 3's packet path.
//
//   build/tests/measure/measure_bare_embree SCENE|spheres:N [WIDTH=512] [THREADS=2] [REPEATS=5] [--packet]

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
#include "tests/measure/tool_scene.h"

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

// One packet of K consecutive rays (a row of the tile) through rtcIntersectK.
template <int K, typename RayHitK, typename Fn>
void tracePacket(RTCScene rtc, RTCIntersectContext* context, const Ray* rays, size_t n, unsigned* primIds, Fn fn) {
  alignas(64) int valid[K];
  alignas(64) RayHitK rh;
  for (int k = 0; k < K; ++k) {
    const Ray& ray = rays[size_t(k) < n ? k : 0];
    valid[k] = size_t(k) < n ? -1 : 0;
    rh.ray.org_x[k] = ray.origin.x, rh.ray.org_y[k] = ray.origin.y, rh.ray.org_z[k] = ray.origin.z;
    rh.ray.dir_x[k] = ray.direction.x, rh.ray.dir_y[k] = ray.direction.y, rh.ray.dir_z[k] = ray.direction.z;
    rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = ray.tMax, rh.ray.mask[k] = ~0u, rh.ray.time[k] = 0.0f;
    rh.ray.flags[k] = 0, rh.ray.id[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  }
  fn(valid, rtc, context, &rh);
  for (size_t k = 0; k < n; ++k) primIds[k] = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? ~0u : rh.hit.primID[k];
}

}  // namespace

int main(int argc, char** argv) try {
  bool packet = false;
  if (argc > 1 && std::string(argv[argc - 1]) == "--packet") packet = true, --argc;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE|spheres:N [WIDTH=512] [THREADS=2] [REPEATS=5] [--packet]\n", argv[0]);
    return 2;
  }
  const std::string sceneName = argv[1];
  const int width = argc > 2 ? std::stoi(argv[2]) : 512;
  const int threads = argc > 3 ? std::stoi(argv[3]) : 2;
  const int repeats = argc > 4 ? std::stoi(argv[4]) : 5;
  if (width <= 0 || threads <= 0 || repeats <= 0) throw std::invalid_argument("WIDTH, THREADS, REPEATS must be > 0");

  const Scene scene = loadToolScene(sceneName);
  const CameraBasis basis = makeCameraBasis(scene.camera, width, width);
  const size_t count = size_t(width) * size_t(width);
  std::vector<Ray> rays(count);
  for (size_t i = 0; i < count; ++i) rays[i] = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));

  RTCDevice device = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
  RTCScene rtc = buildScene(device, scene);
  std::vector<unsigned> primIds(count);
  const int packetWidth = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) ? 16 : 8;
  tbb::task_arena arena(threads);
  double best = std::numeric_limits<double>::infinity();
  size_t hits = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    if (packet) {
      // Tiles of 8 columns by 32 (16) rows, 256 pixels per work item like the other loop; a packet is
      // 2 rows (1 row) of a tile, the rays gathered from and the ids scattered to the image.
      const size_t tilesX = (size_t(width) + 7) / 8, tileH = size_t(packetWidth) / 8 * 16;
      const size_t tilesY = (size_t(width) + tileH - 1) / tileH;
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, tilesX * tilesY, 1), [&](const tbb::blocked_range<size_t>& r) {
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          for (size_t tile = r.begin(); tile < r.end(); ++tile) {
            const size_t x0 = tile % tilesX * 8, y0 = tile / tilesX * tileH;
            const size_t n = std::min<size_t>(8, size_t(width) - x0);
            for (size_t y = y0; y < std::min(y0 + tileH, size_t(width)); y += size_t(packetWidth) / 8) {
              Ray packetRays[16];
              unsigned ids[16];
              size_t m = 0;
              for (size_t yy = y; yy < std::min(y + size_t(packetWidth) / 8, size_t(width)); ++yy)
                for (size_t x = x0; x < x0 + n; ++x) packetRays[m++] = rays[yy * size_t(width) + x];
              if (packetWidth == 16)
                tracePacket<16, RTCRayHit16>(rtc, &context, packetRays, m, ids,
                                             [](const int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit16* h) {
                                               rtcIntersect16(v, s, c, h);
                                             });
              else
                tracePacket<8, RTCRayHit8>(rtc, &context, packetRays, m, ids,
                                           [](const int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit8* h) {
                                             rtcIntersect8(v, s, c, h);
                                           });
              size_t k = 0;
              for (size_t yy = y; yy < std::min(y + size_t(packetWidth) / 8, size_t(width)); ++yy)
                for (size_t x = x0; x < x0 + n; ++x) primIds[yy * size_t(width) + x] = ids[k++];
            }
          }
        });
      });
    } else
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
  std::printf("{\"scene\": \"%s\", \"api\": \"%s\", \"width\": %d, \"threads\": %d, \"repeats\": %d, "
              "\"rays\": %zu, \"hits\": %zu, \"min_ms\": %.3f, \"mrays_per_s\": %.3f}\n",
              sceneName.c_str(), packet ? (packetWidth == 16 ? "rtcIntersect16" : "rtcIntersect8") : "rtcIntersect1",
              width, threads, repeats, count, hits, best, double(count) / best / 1000.0);
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "measure_bare_embree: %s\n", e.what());
  return 1;
}
