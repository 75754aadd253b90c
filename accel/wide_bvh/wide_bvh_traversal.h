#pragma once
// Traversal of the 8-wide BVH: the eight child boxes tested at once, hit
// children visited nearest first from an explicit stack, leaves tested a pack
// of four triangles at once (Möller–Trumbore; the watertight test one
// triangle at a time). Two builds of the same loop (wide_bvh_traverse.inc):
// AVX2 for CPUs that have it, chosen at run time, and portable scalar code.
// Both perform the same float operations in the same order as geometry.h's
// tests, so they return the same hits and counts as each other.
//
// RayStats: steps = inner nodes visited + triangles tested; triangleTests =
// real triangles tested (pack padding is not counted).

#include <span>

#include "accel/geometry/triangle_test.h"
#include "accel/ray_packet.h"
#include "accel/traversal_stats.h"
#include "accel/wide_bvh/wide_bvh.h"

namespace passtrace {

Hit traverseWideBvhScalar(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                          TriangleTest test, RayStats* stats);
// Only on CPUs where wideBvhAvx2Available().
Hit traverseWideBvhAvx2(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                        TriangleTest test, RayStats* stats);
bool wideBvhAvx2Available();
inline constexpr int kWidePacketMax = RayPacket::kMax;  // rays per packet: one bit each in a 64-bit mask
// How a packet leaves the shared stack (Embree's "hybrid" traversal): at an
// inner node that at most `singleRayAt` of its rays still reach, each of them
// walks the node's subtree alone. Few live rays carry the packet's per-node
// bookkeeping for almost no shared work: incoherent AO packets soon thin out.
// At a leaf, a group of eight consecutive rays of which at least
// `acrossRaysAt` reach it tests the leaf one triangle against its eight rays
// per instruction (the classic packet layout) instead of each ray against four
// triangles: coherent rays share leaves, and then a pack costs a fraction of
// its per-ray price. The hits and counts are the same either way.
struct PacketConfig {
  int singleRayAt = 0;   // 0: never; kWidePacketMax: every ray alone from the root
  int acrossRaysAt = 0;  // 0: never; 1: every group with a live ray
  // The same for inner nodes, in any-hit packets (closest-hit ones ignore
  // it): a group of eight whose rays point into one octant (so they share the
  // slabs they enter first) and of which at least `nodesAcrossAt` reach the
  // node tests it one child against the eight rays per instruction instead of
  // each ray against the eight children.
  int nodesAcrossAt = 0;  // 0: never; 1: every one-octant group with a live ray
};
// bvh8-packet's choice, measured with tests/measure/packet_handover.cpp (512²,
// one thread, bunny, Kitchen, Robots): any-hit packets at 4 took 4-8 % less
// time than never for AO rays on Kitchen and Robots (1.5 % more on the bunny)
// and within 5 % either way for shadow rays; closest-hit (primary) packets
// took 0.5-1 % more at 4, so they never hand over. Leaves across rays from 4
// of 8 (tests/measure/ray_kinds.cpp, 512², one thread; 3 to 7 measured, 4
// among the best on every scene; measured before any-hit packets lost their
// entry-distance cull): Cornell's shadow rays 6.8 -> 3.9 ms, Robots' 6.7 ->
// 5.6, Kitchen's 13.1 -> 11.1; primary rays 13-35 % faster on four scenes; the
// bunny's rays 2-3 % slower (docs/bench-speed/NOTES.md, eighth session).
// Inner nodes across rays from 4 of 8 (1, 2, 4, 6 and 8 tried), any-hit
// packets only (tests/measure/ray_kinds.cpp, 512², one thread, against the
// build without, alternated, two rounds): shadow rays on Robots 4.3-4.5 ->
// 3.6 ms, Kitchen 10.3-10.8 -> 9.8-9.9, Cornell 3.4 -> 3.3, the bunny's
// within noise; AO rays within 2 % (few AO groups share an octant). Closest-hit
// packets took 1-4 % longer with it (the least entry distance per child costs
// a horizontal minimum), so only any-hit packets are built with it
// (docs/bench-speed/NOTES.md, tenth session).
inline constexpr PacketConfig kClosestHitPackets{0, 4, 0}, kAnyHitPackets{4, 4, 4};
inline constexpr PacketConfig packetConfigFor(bool anyHit) { return anyHit ? kAnyHitPackets : kClosestHitPackets; }
// A packet's rays (Möller–Trumbore only) sharing one stack; hits and stats
// have one entry per ray (stats are added to). AVX2 only, as above.
void traceWideBvhPacketAvx2(const WideBvh& bvh, const RayPacket& rays, bool anyHit, std::span<Hit> hits,
                            std::span<RayStats> stats, const PacketConfig& config = {});
// Several packets at once. With takeTurns a few walk at a time, taking turns
// a node or leaf each, so that one's cache misses overlap the others' work;
// otherwise one after another. Each packet's hits and counts are the same
// either way (and as traceWideBvhPacketAvx2's).
void traceWideBvhPacketsAvx2(const WideBvh& bvh, std::span<const PacketJob> jobs, bool anyHit,
                             const PacketConfig& config, bool takeTurns);
// bvh8-packet takes turns over trees larger than this. Turns pay where a walk
// waits on memory: the dragon's 66 MB tree and Conference's 24 MB frames
// 0.73x and 0.89x the time (-b 1, against one packet at a time); on the
// bunny, Kitchen and Robots (trees of 5-8 MB, in this machine's 32 MB L3) the
// turns' upkeep made frames up to 1.17x slower (docs/bench-speed/NOTES.md).
inline constexpr size_t kTakeTurnsAboveBytes = size_t(16) << 20;

}  // namespace passtrace
