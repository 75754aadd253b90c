#pragma once
// The surfaces of the ray stream (one element per pixel) and the ray kinds,
// as the kernels in kernels_glsl/ read and write them.

namespace passtrace {

enum RaySurface : int {
  kOriginSurface = 0,   // xyz origin, w ray kind
  kDirectionSurface,    // xyz direction, w tMax
  kStateSurface,        // traversal state; w = 1 while active (read by cull)
  kHitSurface,          // t, u, v, packed triangle id
  kColorSurface,        // accumulated radiance
  kThroughputSurface,   // rgb path weight, w traversal steps so far
  kPendingSurface,      // rgb light awaiting a shadow ray, w triangle tests so far
  kAuxSurface,          // traversal state an accelerator needs beyond kStateSurface
  kRaySurfaceCount
};

// kernels_glsl/ray_kinds.glsl
enum class RayKind : int { None = 0, Nearest = 1, Shadow = 2 };

}  // namespace passtrace
