#pragma once
// The shading rules of thesis 4.2 for one stream element and one bounce, as
// kernels_glsl/shade.frag applies them on the GPU; the CPU renderer calls
// this for every element after each trace.

#include "accel/geometry/geometry.h"
#include "accel/ray_stream_layout.h"
#include "scenes/scene.h"

namespace passtrace {

// One pixel's path: its current ray and what it has gathered so far.
struct PathState {
  Ray ray;
  RayKind kind = RayKind::Nearest;
  glm::vec3 color{0.0f};
  glm::vec3 throughput{1.0f};
  glm::vec3 pending{0.0f};  // light added if the shadow ray reaches it
  uint64_t steps = 0;       // traversal steps of all rays traced so far
  uint64_t triangleTests = 0;
};

// Offset of secondary ray origins along the normal, relative to the scene size.
float secondaryRayEpsilon(const Scene& scene);

// Resolves `hit` for the element's ray and sets its next ray (kind None if none).
void shadeElement(const Scene& scene, float epsilon, bool lastBounce, const Hit& hit, PathState& path);

}  // namespace passtrace
