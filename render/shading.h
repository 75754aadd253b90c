#pragma once
// The shading rules of thesis 4.2 for one stream element and one bounce, as
// kernels_glsl/shade.frag applies them on the GPU; the CPU renderer calls
// this for every element after each trace.

#include <array>
#include <span>

#include "accel/geometry/geometry.h"
#include "accel/ray_stream_layout.h"
#include "render/shading_config.h"
#include "render/shading_table.h"
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
  int depth = 1;   // whitted: the current ray's depth in the ray tree (primary = 1)
  int sample = 0;  // ao: the AO ray being traced
  glm::vec3 aoNormal{0.0f};  // ao: the primary hit's normal the samples are drawn about
};

// Whitted: the rays a pixel has yet to trace: reflection and refraction
// (Nearest, with their throughput) and shadow rays (Shadow, `throughput`
// holding the light they carry).
struct PendingRay {
  Ray ray;
  glm::vec3 throughput{1.0f};
  int depth = 1;
  RayKind kind = RayKind::Nearest;
};
struct WhittedStack {
  std::array<PendingRay, kWhittedStackSize> entries;
  int count = 0;
};

// Offset of secondary ray origins along the normal, relative to the scene size.
float secondaryRayEpsilon(const Scene& scene);

// Resolves `hit` for the element's ray and sets its next ray (kind None if none).
// `table` (makeShadingTable(scene)), when given, is read instead of the hit
// triangle and its material id: the same values, one load. Also for the two below.
void shadeElement(const Scene& scene, float epsilon, bool lastBounce, const Hit& hit, PathState& path,
                  std::span<const ShadingEntry> table = {});

// A primary ray's colour when it is its path's only bounce (thesis shading,
// -b 1): what shadeElement leaves in a fresh PathState on its last bounce,
// bit for bit, without the path state.
glm::vec3 shadePrimaryOnly(const Scene& scene, float epsilon, const Ray& ray, const Hit& hit,
                           std::span<const ShadingEntry> table = {});

// --shading whitted, as kernels_glsl/shade_whitted.frag. Order per nearest hit:
// ambient; the pending rays pushed (refraction, then reflection on top);
// then per light that can light the point (pending = diffuse + Phong
// highlight) a shadow ray: the first light's is traced next, the others'
// pushed last light first; when the element has no ray, the top pending ray
// is popped. Children are spawned while depth < maxDepth (-b).
void shadeWhitted(const Scene& scene, float epsilon, int maxDepth, const Hit& hit, PathState& path,
                  WhittedStack& stack, std::span<const ShadingEntry> table = {});

// Whitted's lights: Scene::lights (the first kWhittedMaxLights), or Scene::light alone.
int whittedLightCount(const Scene& scene);
const PointLight& whittedLight(const Scene& scene, int k);

// --shading ao, as kernels_glsl/shade_ao.frag: a primary hit starts the AO
// rays (any-hit, tMax = distance) about its normal; each unoccluded one adds
// 1/samples to the grey; a primary miss shows the background.
void shadeAo(const Scene& scene, float epsilon, int samples, float distance, uint32_t pixel, const Hit& hit,
             PathState& path, std::span<const ShadingEntry> table = {});

// The AO rays' length: config.aoDistance, or kAoDistanceFraction of the scene's box diagonal.
float aoDistance(const Scene& scene, const ShadingConfig& config);

}  // namespace passtrace
