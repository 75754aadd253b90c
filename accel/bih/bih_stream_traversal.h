#pragma once
// The BIH traversal on the CPU, step for step as kernels_glsl/bih/bih_traversal.glsl
// runs it on the GPU, over the same texels (bih_texels.h): the GPU and the CPU
// must find the same hits and count the same steps (tests/gl/gpu_traversal_test.cpp).
// It is also the bih row's CPU traversal. Why a copy and not one source: see
// accel/kd/kd_stream_traversal.h.
//
// A ray keeps an interval [tMin, tMax] at the node it is at. At an inner node
// the two clip planes give each child's part of the interval; a ray may miss
// both children (the gap between the planes), enter one, or both: then the
// near child now and the far one (node, tMin, tMax) on a stack as deep as the
// tree. Nothing ends at the first leaf with a hit, as children overlap: a
// stacked child whose interval starts beyond the current hit is dropped when
// popped. Plane parameters are widened by kBihSlack (relative) so rounding
// never loses a child the ray touches at its plane.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

inline constexpr float kBihSlack = 0x1p-20f;

struct BihStreamData {
  Aabb sceneBox;
  std::span<const glm::vec4> nodes, lists, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;  // as the kernel is compiled
};

// A ray's traversal state between passes: the state and aux surfaces and the
// storage-buffer stack (bih_ray_record.glsl).
struct BihStreamCursor {
  static constexpr float kModeDown = -1.0f;
  struct Entry {
    uint32_t node;
    float tMin, tMax;
  };
  uint32_t node = 0;
  float mode = kModeDown;  // kModeDown, or a packed list entry while testing a leaf
  float tMin = 0, tMax = 0;
  Hit best;
  RayStats stats;
  bool done = false;
  std::vector<Entry> stack;
};

// bih_init.frag: clips the ray to the scene box; done if it misses.
BihStreamCursor bihStreamStart(const BihStreamData& data, const Ray& ray);
// Up to maxSteps steps of bih_traverse.frag; returns true while work remains.
bool bihStreamSteps(const BihStreamData& data, const Ray& ray, bool anyHit, BihStreamCursor& cursor,
                    uint32_t maxSteps);
// Start and steps to the end.
Hit traverseBihStream(const BihStreamData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
