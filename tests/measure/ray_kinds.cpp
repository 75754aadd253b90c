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

// One way of tracing a set's packets: returns the rays found hit or blocked.
struct Path {
  std::string name;
  std::function<size_t(const PacketSet&)> trace;
};

size_t countFound(std::span<const Hit> hits) {
  return size_t(std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.found(); }));
}

// Packets handed over as the renderer hands a work item's tiles over: one at
// a time (tracePacket), or packetsAtOnce() together (tracePackets).
Path packets(std::string name, const CpuAccelerator& accel) {
  const size_t group = size_t(std::max(1, accel.packetsAtOnce()));
  return {std::move(name), [&accel, group](const PacketSet& set) {
            std::vector<Hit> hits(group * RayPacket::kMax);
            std::vector<RayStats> stats(hits.size());
            std::vector<PacketJob> jobs(group);
            size_t found = 0;
            for (size_t first = 0; first < set.packets.size(); first += group) {
              const size_t n = std::min(group, set.packets.size() - first);
              for (size_t k = 0; k < n; ++k)
                jobs[k] = {&set.packets[first + k], hits.data() + k * RayPacket::kMax, stats.data() + k * RayPacket::kMax};
              if (group == 1) {
                const size_t m = size_t(set.packets[first].count);
                accel.tracePacket(set.packets[first], set.anyHit, std::span<Hit>(hits.data(), m),
                                  std::span<RayStats>(stats.data(), m));
              } else {
                accel.tracePackets(std::span<const PacketJob>(jobs.data(), n), set.anyHit);
              }
              for (size_t k = 0; k < n; ++k)
                found += countFound(std::span<const Hit>(jobs[k].hits, size_t(jobs[k].rays->count)));
            }
            return found;
          }};
}

Path singleRays(std::string name, const CpuAccelerator& accel) {
  return {std::move(name), [&accel](const PacketSet& set) {
            size_t found = 0;
            for (const RayPacket& packet : set.packets)
              for (int k = 0; k < packet.count; ++k) found += accel.intersect(packet.ray(k), set.anyHit, nullptr).found();
            return found;
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
    for (int r = 0; r < args->repeats; ++r)
      for (size_t p = 0; p < paths.size(); ++p) {
        const auto start = std::chrono::steady_clock::now();
        const size_t count = paths[p].trace(set);
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
