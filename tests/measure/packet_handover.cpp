// bvh8-packet's packet traversal against PacketConfig::singleRayAt (when a
// packet hands its last live rays over to single-ray traversal), on the rays
// the CPU renderer traces: primary rays in 8x4 tiles, and from their hits
// shadow rays to the light and AO rays (the renderer's directions and length),
// each in packets of one 8x8 tile. Leaves as bvh8-packet tests them
// (packetConfigFor(anyHit).acrossRaysAt). One thread; the settings alternate within
// each repeat so that they share the machine's state; each cell is the
// minimum over the repeats. Prints one JSON line per ray kind.
//
//   build/tests/measure/measure_packet_handover SCENE|spheres:N [WIDTH=512] [REPEATS=7] [AO_SAMPLES=4]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "scenes/scene_registry.h"
#include "tests/measure/renderer_rays.h"
#include "tests/measure/tool_scene.h"

namespace {

using namespace passtrace;

constexpr int kSettings[] = {0, 1, 2, 4, 8, 16, 64};

}  // namespace

int main(int argc, char** argv) try {
  const std::optional<RayToolArgs> args = parseRayToolArgs(argc, argv, 7);
  if (!args) return 2;
  if (!wideBvhAvx2Available()) throw std::runtime_error("packets need AVX2");

  const Scene scene = loadToolScene(args->scene);
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(scene.triangles), scene.triangles);
  const std::vector<PacketSet> sets = rendererRays(scene, bvh, args->width, args->aoSamples);

  for (const PacketSet& set : sets) {
    constexpr size_t kSettingCount = std::size(kSettings);
    double best[kSettingCount];
    std::fill(best, best + kSettingCount, std::numeric_limits<double>::infinity());
    std::vector<Hit> out(kWidePacketMax);
    std::vector<RayStats> stats(kWidePacketMax);
    size_t found[kSettingCount] = {};
    for (int r = 0; r < args->repeats; ++r)
      for (size_t s = 0; s < kSettingCount; ++s) {
        size_t hitCount = 0;
        const auto start = std::chrono::steady_clock::now();
        for (const RayPacket& packet : set.packets) {
          const size_t m = size_t(packet.count);
          traceWideBvhPacketAvx2(bvh, packet, set.anyHit, std::span<Hit>(out.data(), m),
                                 std::span<RayStats>(stats.data(), m),
                                 PacketConfig{kSettings[s], packetConfigFor(set.anyHit).acrossRaysAt});
          for (size_t k = 0; k < m; ++k) hitCount += out[k].found();
        }
        best[s] = std::min(best[s], std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        found[s] = hitCount;
      }
    // Every setting must find the same rays blocked or hit; else the timing compares different work.
    for (size_t s = 1; s < kSettingCount; ++s)
      if (found[s] != found[0]) throw std::runtime_error(set.kind + ": settings disagree on the hits");
    std::printf("{\"scene\": \"%s\", \"kind\": \"%s\", \"rays\": %zu, \"packets\": %zu, \"hits\": %zu, \"ms\": {", args->scene.c_str(),
                set.kind.c_str(), set.rays, set.packets.size(), found[0]);
    for (size_t s = 0; s < kSettingCount; ++s)
      std::printf("%s\"%d\": %.2f", s ? ", " : "", kSettings[s], best[s]);
    std::printf("}}\n");
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "measure_packet_handover: %s\n", e.what());
  return 1;
}
