#pragma once
// kd-ropes' stackless traversal (Popov et al. 2007) on the CPU, step for step as
// kernels_glsl/kd/kd_ropes_traversal.glsl runs it on the GPU over the same texels
// (kd_ropes.h), so both find the same hits and count the same steps (tests
// compare them; why a copy and not one source: kd_stream_traversal.h).
//
// A ray's state is a node (texel offset), a mode and its entry distance tEntry:
//   mode DOWN: descending from `node` to the leaf holding the entry point;
//   mode >= 0: testing the leaf's list, at packed list entry `mode`.
// After a leaf's list: its exit distance from the three box faces on the side
// the ray heads to; done if the best hit is no farther or the ray ends there,
// else on through the exit face's rope (none: the ray leaves the scene).
//
// The descent compares the entry point with each split parametrically:
// tSplit = (split - origin) * invDir, the very expression a leaf's exit uses, so
// a ray leaving through a face enters the next leaf's subtree on the far side
// of every plane through that face (no rounding disagreement between the two).
// An origin on a plane goes to the side it heads to.

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct KdRopesData {
  Aabb sceneBox;
  std::span<const glm::vec4> nodes, lists, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
  // Robustness bound: a ray still going after this many steps is stopped
  // (a correct traversal never gets there; see kdRopesMaxSteps).
  uint64_t maxSteps = 0;
};

// No ray takes more steps: each leaf is entered at most once per rope, through
// at most depth descent steps, plus every list entry and one exit per leaf.
uint64_t kdRopesMaxSteps(size_t leaves, uint32_t depth, size_t listEntries);

struct KdRopesCursor {
  static constexpr float kModeDown = -1.0f;
  uint32_t node = 0;  // texel offset; 0 is the root
  float mode = kModeDown;
  float tEntry = 0, sceneMax = 0;
  Hit best;
  RayStats stats;
  bool done = false;
};

// kd_init.frag: clips the ray to the scene box; done if it misses.
KdRopesCursor kdRopesStart(const KdRopesData& data, const Ray& ray);
// Up to maxSteps steps of the kernel; returns true while work remains.
bool kdRopesSteps(const KdRopesData& data, const Ray& ray, bool anyHit, KdRopesCursor& cursor, uint32_t maxSteps);
Hit traverseKdRopes(const KdRopesData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
