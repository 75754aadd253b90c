#pragma once
// Which rays a pixel's shading spawns (--shading) and the ambient-occlusion
// settings; both renderers read the same config so their images agree.

#include <optional>
#include <string_view>

namespace passtrace {

enum class ShadingMode {
  Thesis,   // thesis 4.2: diffuse, one shadow ray, mirrors; -b traces per path (the default, today's images)
  Whitted,  // reflection and refraction with Fresnel, shadow rays, Phong highlights; -b = depth of the ray tree
  Ao,       // ambient occlusion: --ao-samples any-hit rays per primary hit; -b is not read
};

std::optional<ShadingMode> shadingModeByName(std::string_view name);
const char* shadingModeName(ShadingMode mode);

struct ShadingConfig {
  ShadingMode mode = ShadingMode::Thesis;
  int aoSamples = 16;      // the seed's 16 cosine-distributed rays per primary hit
  float aoDistance = 0.0f;  // > 0: the AO rays' tMax; 0: kAoDistanceFraction of the scene's box diagonal
};

// Default AO ray length as a fraction of the scene's bounding-box diagonal:
// long enough to darken corners and contacts, short enough that open scenes
// are not grey everywhere.
inline constexpr float kAoDistanceFraction = 0.1f;

// Whitted: pending rays kept per pixel (reflection, refraction, and the
// shadow rays to the second and further lights). A push onto a full stack
// drops the new ray (both renderers).
inline constexpr int kWhittedStackSize = 16;
// Floats per entry of the GPU renderer's Whitted stacks (shade_whitted.frag:
// origin and depth, direction and tMax, throughput and kind).
inline constexpr int kWhittedStackFloats = 12;
// Whitted: shadow rays go to the scene's first this many lights (Scene::lights).
inline constexpr int kWhittedMaxLights = 8;
// Whitted: a branch whose throughput falls below this in every channel is not
// traced (it cannot change an 8-bit pixel by more than one step).
inline constexpr float kWhittedMinThroughput = 1.0f / 512.0f;

}  // namespace passtrace
