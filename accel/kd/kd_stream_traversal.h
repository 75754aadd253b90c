#pragma once
// kd-restart and kd-backtrack (Foley & Sugerman, thesis 8.2-8.5), and
// kd-pushdown, kd-shortstack, kd-pushdown-shortstack and kd-stack (Horn et al.
// 2007, seed 003 ch. 6) on the CPU, step for step as
// kernels_glsl/kd/kd_traversal.glsl runs them on the GPU, over
// the same texels (accel/kd/kd_texels.h). They exist to debug the kernels: the
// GPU and the CPU must find the same hits and count the same steps.
//
// Why a copy and not one source: the kernel resumes across passes (its state
// packed into RGBA32F surfaces, at most -l steps per pass, the stack-free
// formulation the thesis needs), the mirror runs each ray to completion; a
// GLSL-compatible C++ subset shared by both would need macros for texel
// fetches, `precise` and the pass structure, and hide the very loop a reader
// compares with the thesis. The copy is held to the kernel instead:
// tests/gpu_traversal_test.cpp checks, for every registry row with a stream
// kernel, the same hits and the same step and triangle-test counts per ray.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

// Restart: after a leaf without a hit, descend again from the root over the
//   rest of the ray. PushDown: from the push-down root instead, the deepest
//   node entered while the descent met no node with both children to visit.
// ShortStack: a circular stack of stackSize far children (node, tMin, tMax);
//   a push onto a full stack drops the oldest entry, an empty stack restarts
//   from the root. PushDownShortStack: restarts from the push-down root.
// Stack: a stack as deep as the tree, which never overflows.
// Compact: Stack over 8-byte nodes (kd_compact_node.h), the seed-002 layout.
enum class KdStreamVariant { Restart, Backtrack, PushDown, ShortStack, PushDownShortStack, Stack, Compact };

inline bool kdRestartsFromPushDownRoot(KdStreamVariant v) {
  return v == KdStreamVariant::PushDown || v == KdStreamVariant::PushDownShortStack;
}
inline bool kdHasStack(KdStreamVariant v) {
  return v == KdStreamVariant::ShortStack || v == KdStreamVariant::PushDownShortStack || v == KdStreamVariant::Stack ||
         v == KdStreamVariant::Compact;
}
// Whether the kernel keeps a per-ray record in a storage buffer (kd_ray_record.glsl).
inline bool kdHasRayRecord(KdStreamVariant v) { return kdRestartsFromPushDownRoot(v) || kdHasStack(v); }

// The data the kernel reads: node texels (1 per node for restart, 3 for
// backtrack, half a texel for compact), reference-list texels and triangle texels (3 per triangle).
struct KdStreamData {
  KdStreamVariant variant = KdStreamVariant::Restart;
  Aabb sceneBox;
  std::span<const glm::vec4> nodes, lists, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;  // as the kernel is compiled
  uint32_t stackSize = 0;  // stack entries of the stack variants (>= 1 for them)
};

// The stack variants' stack, as kd_ray_record.glsl keeps it: `size` slots
// used circularly, so a push onto a full stack overwrites the oldest entry.
struct KdCircularStack {
  struct Entry {
    uint32_t node;
    float tMin, tMax;  // the far child's interval: from the split to the old tMax
  };
  std::vector<Entry> slots;
  uint32_t top = 0;    // the slot the next push writes
  uint32_t count = 0;  // live entries, <= slots.size()

  explicit KdCircularStack(uint32_t size = 0) : slots(size) {}
  bool empty() const { return count == 0; }
  void push(const Entry& e) {
    const uint32_t size = uint32_t(slots.size());
    slots[top] = e;
    top = (top + 1) % size;
    count = count < size ? count + 1 : size;
  }
  // The latest entry; the stack must not be empty.
  Entry pop() {
    const uint32_t size = uint32_t(slots.size());
    top = (top + size - 1) % size;
    --count;
    return slots[top];
  }
};

// A ray's traversal state between passes (the kernel's state and aux surfaces).
struct KdStreamCursor {
  static constexpr float kModeDown = -1.0f, kModeUp = -2.0f;
  uint32_t node = 0;
  float mode = kModeDown;  // kModeDown, kModeUp, or a packed list entry
  float tMin = 0, tMax = 0, sceneMax = 0;
  Hit best;
  RayStats stats;
  bool done = false;
  // The kernel's storage-buffer record (kd_ray_record.glsl).
  uint32_t root = 0;      // where a restart descends from
  bool pushDown = true;   // no node with both children to visit met in this descent
  KdCircularStack stack;  // the stack variants' far children
};

// kd_init.frag: clips the ray to the scene box; done if it misses.
KdStreamCursor kdStreamStart(const KdStreamData& data, const Ray& ray);

// Up to maxSteps steps of kd_traverse.frag; returns true while work remains.
bool kdStreamSteps(const KdStreamData& data, const Ray& ray, bool anyHit, KdStreamCursor& cursor, uint32_t maxSteps);

// Start and steps to the end.
Hit traverseKdStream(const KdStreamData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
