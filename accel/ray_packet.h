#pragma once
// A packet of rays as a structure of arrays: each field one lane per ray, the
// layout SIMD traversals load eight rays at a time from (and Embree's
// RTCRayHitK copies lane for lane). The CPU renderer writes its tiles' rays
// straight into it: primary rays as eight camera directions per row at once,
// instead of a Ray per pixel copied and transposed again by the tracer.

#include <algorithm>
#include <cstddef>
#include <span>

#include "accel/geometry/geometry.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct RayPacket {
  static constexpr int kMax = 64;  // one bit per ray in a 64-bit mask
  int count = 0;
  // Lanes past `count` hold zeros or rays set earlier: SIMD code may load them
  // with their group of eight (bvh8-packet's leaves) but never uses what they give.
  alignas(32) float ox[kMax] = {}, oy[kMax] = {}, oz[kMax] = {};
  alignas(32) float dx[kMax] = {}, dy[kMax] = {}, dz[kMax] = {};
  alignas(32) float tMax[kMax] = {};

  void set(int i, const Ray& r) {
    ox[i] = r.origin.x, oy[i] = r.origin.y, oz[i] = r.origin.z;
    dx[i] = r.direction.x, dy[i] = r.direction.y, dz[i] = r.direction.z;
    tMax[i] = r.tMax;
  }
  void push(const Ray& r) { set(count++, r); }
  Ray ray(int i) const { return Ray{{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tMax[i]}; }

  // The first min(kMax, rays.size()) rays.
  static RayPacket of(std::span<const Ray> rays) {
    RayPacket packet;
    for (const Ray& r : rays.first(std::min(rays.size(), size_t(kMax)))) packet.push(r);
    return packet;
  }
};

// One packet of several handed to a tracer at once: its rays, and where its
// hits and stats go (one entry per ray; stats are added to).
struct PacketJob {
  const RayPacket* rays;
  Hit* hits;
  RayStats* stats;
};

}  // namespace passtrace
