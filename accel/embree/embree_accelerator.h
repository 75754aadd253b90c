#pragma once
// Intel Embree 3 as a CpuAccelerator: the CPU baseline a user would pick
// instead of passtrace's own structures. One RTCDevice and one RTCScene with a
// single triangle geometry (RTC_BUILD_QUALITY_HIGH, committed once), owned by
// the accelerator and released in its destructor.
//
// Differences from passtrace's own accelerators, all deliberate:
//
// * Geometry is copied into Embree-owned buffers (3 vertices per triangle in
//   scene order, so Embree's primID is the scene triangle index). Unlike the
//   other accelerators this one therefore does not hold a span of the caller's
//   triangles; it stays valid after they are gone.
// * Closest hit (anyHit false): rtcIntersect1 with tnear = 0 and tfar just
//   below tMax, giving Hit{t, u, v, id = primID}; u and v weight the second
//   and third vertex, as everywhere in passtrace. Embree accepts hits with
//   tnear < t <= tfar, so tfar is set to the largest float below a finite tMax
//   to keep passtrace's rule 0 < t < tMax (an infinite tMax stays infinite;
//   tMax <= 0 or NaN returns no hit without calling Embree). Embree tests the
//   range before dividing and then divides with an approximate reciprocal, so
//   its t can be an ulp or so off Möller–Trumbore's (a hit exactly at t = 1
//   reports 0.99999994); the returned t is clamped below tMax.
// * Any hit (anyHit true): rtcOccluded1, which reports only found-or-not. An
//   occluded ray returns Hit{t = 0, u = 0, v = 0, id = 0}: found() is true but
//   t, u, v and id carry NO information about which triangle was hit or where
//   (id 0 is merely a valid value). A ray that is not occluded returns
//   Hit{t = tMax, id = kNoHit}, like brute force.
// * Packets (packetSize() / tracePacket(), which the CPU renderer uses for
//   primary and shadow tiles): rtcIntersect16 / rtcOccluded16, or 8 / 4 wide
//   where Embree runs no wider natively; the same rules per lane, and the
//   same bits as the single-ray calls (tests/unit/embree_packet_test.cpp).
// * Embree's triangle test is not passtrace's Möller–Trumbore: on shared edges
//   and exact ties the triangle chosen (or whether a grazing hit counts) may
//   differ in the last bits; tests compare with a t-tie tolerance.
// * RayStats: Embree reports no traversal steps or triangle tests, so stats
//   is never touched.
// * AccelStats: name "embree"; buildMs covers device creation, buffer setup
//   and the scene build (steady_clock); floatsPerTriangle is 0 because Embree
//   does not report its memory layout; nodes, leaves and depth are 0 (not
//   reported); references is the triangle count.
//
// Errors reported by Embree during construction (including a device that
// cannot be created) throw std::runtime_error with a one-line message
// starting "embree: ". In a build without Embree (PASSTRACE_HAVE_EMBREE 0)
// makeEmbreeAccelerator() always throws std::runtime_error.

#include <memory>
#include <span>

#include "accel/cpu_accelerator.h"

namespace passtrace {

// Builds an Embree scene over tris (may be empty: nothing is ever hit).
// Safe to intersect from many threads at once once built.
std::unique_ptr<CpuAccelerator> makeEmbreeAccelerator(std::span<const Triangle> tris);
// The registry's factory (-r 3): Embree reads no build parameter.
std::unique_ptr<CpuAccelerator> makeEmbreeCpu(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
