// bvh8-packet's packet traversal against PacketConfig::singleRayAt (when a
// packet hands its last live rays over to single-ray traversal), on the rays
// the CPU renderer traces: primary rays in 8x4 tiles, and from their hits
// shadow rays to the light and AO rays (the renderer's directions and length),
// each in packets of one 8x8 tile. One thread; the settings alternate within
// each repeat so that they share the machine's state; each cell is the
// minimum over the repeats. Prints one JSON line per ray kind.
//
//   build/tests/measure/measure_packet_handover SCENE [WIDTH=512] [REPEATS=7] [AO_SAMPLES=4]

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
#include "render/ao_sampling.h"
#include "render/camera.h"
#include "render/shading.h"
#include "scenes/scene_registry.h"

namespace {

using namespace passtrace;

constexpr int kSettings[] = {0, 1, 2, 4, 8, 16, 64};

// The rays of one kind, grouped into the packets the renderer would form.
struct PacketSet {
  std::string kind;
  bool anyHit = false;
  std::vector<RayPacket> packets;
  size_t rays = 0;
};

// Pixel indices tile by tile (tileW x tileH, row by row inside a tile).
std::vector<std::vector<size_t>> tiles(int width, int tileW, int tileH) {
  std::vector<std::vector<size_t>> out;
  for (int y0 = 0; y0 < width; y0 += tileH)
    for (int x0 = 0; x0 < width; x0 += tileW) {
      std::vector<size_t>& t = out.emplace_back();
      for (int y = y0; y < std::min(y0 + tileH, width); ++y)
        for (int x = x0; x < std::min(x0 + tileW, width); ++x) t.push_back(size_t(y) * size_t(width) + size_t(x));
    }
  return out;
}

void add(PacketSet& set, const std::vector<Ray>& packet) {
  if (packet.empty()) return;
  set.rays += packet.size();
  set.packets.push_back(RayPacket::of(packet));
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE [WIDTH=512] [REPEATS=7] [AO_SAMPLES=4]\n", argv[0]);
    return 2;
  }
  const int width = argc > 2 ? std::stoi(argv[2]) : 512;
  const int repeats = argc > 3 ? std::stoi(argv[3]) : 7;
  const int aoSamples = argc > 4 ? std::stoi(argv[4]) : 4;
  if (width <= 0 || repeats <= 0 || aoSamples <= 0) throw std::invalid_argument("WIDTH, REPEATS, AO_SAMPLES must be > 0");
  if (!wideBvhAvx2Available()) throw std::runtime_error("packets need AVX2");

  const Scene scene = loadScene(argv[1]);
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(scene.triangles), scene.triangles);
  const CameraBasis basis = makeCameraBasis(scene.camera, width, width);
  const size_t count = size_t(width) * size_t(width);
  std::vector<Ray> primary(count);
  std::vector<Hit> hits(count);
  for (size_t i = 0; i < count; ++i) {
    primary[i] = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));
    hits[i] = traverseWideBvhAvx2(bvh, scene.triangles, primary[i], false, TriangleTest::MollerTrumbore, nullptr);
  }

  // The hit point lifted off its surface along the normal facing the ray, as render/shading.cpp does.
  const float epsilon = secondaryRayEpsilon(scene), aoLength = aoDistance(scene, ShadingConfig{});
  auto lifted = [&](size_t i, glm::vec3& origin, glm::vec3& normal) {
    if (!hits[i].found()) return false;
    const glm::vec3 d = primary[i].direction;
    const glm::vec3 g = glm::normalize(scene.triangles[hits[i].id].geometricNormal());
    normal = glm::dot(g, d) > 0.0f ? -g : g;
    origin = primary[i].origin + hits[i].t * d + epsilon * normal;
    return true;
  };
  PacketSet sets[3] = {{"primary", false, {}, 0}, {"shadow", true, {}, 0}, {"ao", true, {}, 0}};
  for (const std::vector<size_t>& tile : tiles(width, 8, 4)) {
    std::vector<Ray> packet;
    for (size_t i : tile) packet.push_back(primary[i]);
    add(sets[0], packet);
  }
  for (const std::vector<size_t>& tile : tiles(width, 8, 8)) {
    std::vector<Ray> shadow;
    std::vector<std::vector<Ray>> ao{size_t(aoSamples)};
    for (size_t i : tile) {
      glm::vec3 origin, normal;
      if (!lifted(i, origin, normal)) continue;
      const glm::vec3 toLight = scene.light.position - origin;
      const float distance = glm::length(toLight);
      if (glm::dot(normal, toLight) > 0.0f) shadow.push_back(Ray{origin, toLight / distance, distance});
      for (int s = 0; s < aoSamples; ++s)
        ao[size_t(s)].push_back(Ray{origin, aoDirection(normal, aoRandom(uint32_t(i), uint32_t(s))), aoLength});
    }
    add(sets[1], shadow);
    for (const std::vector<Ray>& packet : ao) add(sets[2], packet);
  }

  for (const PacketSet& set : sets) {
    constexpr size_t kSettingCount = std::size(kSettings);
    double best[kSettingCount];
    std::fill(best, best + kSettingCount, std::numeric_limits<double>::infinity());
    std::vector<Hit> out(kWidePacketMax);
    std::vector<RayStats> stats(kWidePacketMax);
    size_t found[kSettingCount] = {};
    for (int r = 0; r < repeats; ++r)
      for (size_t s = 0; s < kSettingCount; ++s) {
        size_t hitCount = 0;
        const auto start = std::chrono::steady_clock::now();
        for (const RayPacket& packet : set.packets) {
          const size_t m = size_t(packet.count);
          traceWideBvhPacketAvx2(bvh, packet, set.anyHit, std::span<Hit>(out.data(), m),
                                 std::span<RayStats>(stats.data(), m), PacketConfig{kSettings[s]});
          for (size_t k = 0; k < m; ++k) hitCount += out[k].found();
        }
        best[s] = std::min(best[s], std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        found[s] = hitCount;
      }
    // Every setting must find the same rays blocked or hit; else the timing compares different work.
    for (size_t s = 1; s < kSettingCount; ++s)
      if (found[s] != found[0]) throw std::runtime_error(set.kind + ": settings disagree on the hits");
    std::printf("{\"scene\": \"%s\", \"kind\": \"%s\", \"rays\": %zu, \"packets\": %zu, \"hits\": %zu, \"ms\": {", argv[1],
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
