// Traversal alone, per ray kind, on the rays the CPU renderer traces
// (renderer_rays.h): bvh8-packet's packets and bvh8's single rays against
// Embree's single-ray calls (rtcIntersect1 / rtcOccluded1) and its packets
// (rtcIntersect16 / rtcOccluded16, as -r 3 traces them). A frame with shadow
// or AO rays also traces primary rays and shades, which can hide a slower
// shadow traversal behind a faster primary one; this separates them. One
// thread; the paths alternate within each repeat; each cell is the minimum
// over the repeats. Prints one JSON line per kind: ms per path and the rays
// each path found hit or blocked (Embree's triangle test may differ on ties).
// Without Embree the Embree paths are left out.
//
//   build/tests/measure/measure_ray_kinds SCENE|spheres:N [WIDTH=512] [REPEATS=5] [AO_SAMPLES=4]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "accel/registry.h"
#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "scenes/scene_registry.h"
#include "tests/measure/renderer_rays.h"
#include "tests/measure/tool_scene.h"

namespace {

using namespace passtrace;

// One way of tracing a packet's rays into hits.
struct Path {
  std::string name;
  std::function<void(const RayPacket&, bool anyHit, std::span<Hit>)> trace;
};

Path packets(std::string name, const CpuAccelerator& accel) {
  return {std::move(name), [&accel](const RayPacket& packet, bool anyHit, std::span<Hit> hits) {
            RayStats stats[RayPacket::kMax];
            accel.tracePacket(packet, anyHit, hits, std::span<RayStats>(stats, hits.size()));
          }};
}

Path singleRays(std::string name, const CpuAccelerator& accel) {
  return {std::move(name), [&accel](const RayPacket& packet, bool anyHit, std::span<Hit> hits) {
            for (int k = 0; k < packet.count; ++k) hits[size_t(k)] = accel.intersect(packet.ray(k), anyHit, nullptr);
          }};
}

}  // namespace

int main(int argc, char** argv) try {
  const std::optional<RayToolArgs> args = parseRayToolArgs(argc, argv, 5);
  if (!args) return 2;
  if (!wideBvhAvx2Available()) throw std::runtime_error("bvh8-packet needs AVX2");

  const Scene scene = loadToolScene(args->scene);
  const std::vector<PacketSet> sets =
      rendererRays(scene, collapseToWideBvh(buildBinnedSahBvh(scene.triangles), scene.triangles), args->width,
                   args->aoSamples);
  const std::unique_ptr<CpuAccelerator> packet = makeCpuStructure("bvh8-packet", scene.triangles);
  const std::unique_ptr<CpuAccelerator> single = makeCpuStructure("bvh8", scene.triangles);
  std::vector<Path> paths = {packets("bvh8-packet", *packet), singleRays("bvh8", *single)};
  std::unique_ptr<CpuAccelerator> embree;
  try {
    embree = makeEmbreeAccelerator(scene.triangles);
    paths.push_back(singleRays("embree-1", *embree));
    paths.push_back(packets("embree-packets", *embree));
  } catch (const std::runtime_error&) {  // a build without Embree: passtrace's paths only
  }

  for (const PacketSet& set : sets) {
    std::vector<double> best(paths.size(), std::numeric_limits<double>::infinity());
    std::vector<size_t> found(paths.size());
    std::vector<Hit> hits(RayPacket::kMax);
    for (int r = 0; r < args->repeats; ++r)
      for (size_t p = 0; p < paths.size(); ++p) {
        size_t count = 0;
        const auto start = std::chrono::steady_clock::now();
        for (const RayPacket& rays : set.packets) {
          const std::span<Hit> out(hits.data(), size_t(rays.count));
          paths[p].trace(rays, set.anyHit, out);
          for (const Hit& h : out) count += h.found();
        }
        best[p] = std::min(best[p], std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        found[p] = count;
      }
    // passtrace's two paths run the same tests: they must agree, or the timing compares different work.
    if (found[0] != found[1]) throw std::runtime_error(set.kind + ": bvh8-packet and bvh8 disagree on the hits");
    std::printf("{\"scene\": \"%s\", \"kind\": \"%s\", \"rays\": %zu, \"packets\": %zu, \"ms\": {", args->scene.c_str(),
                set.kind.c_str(), set.rays, set.packets.size());
    for (size_t p = 0; p < paths.size(); ++p) std::printf("%s\"%s\": %.2f", p ? ", " : "", paths[p].name.c_str(), best[p]);
    std::printf("}, \"found\": {");
    for (size_t p = 0; p < paths.size(); ++p) std::printf("%s\"%s\": %zu", p ? ", " : "", paths[p].name.c_str(), found[p]);
    std::printf("}}\n");
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "measure_ray_kinds: %s\n", e.what());
  return 1;
}
