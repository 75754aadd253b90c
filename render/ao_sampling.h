#pragma once
// Ambient-occlusion directions from a per-pixel integer hash, computed
// identically by kernels_glsl/ao_sampling.glsl: both renderers trace the same
// rays, so their AO images agree.

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace passtrace {

// PCG-RXS-M-XS 32 (O'Neill 2014; Jarzynski & Olano 2020's hash form).
inline uint32_t pcgHash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Two uniform numbers in [0, 1) for sample `sample` of pixel `pixel` (y * width + x),
// 24 bits each so the float conversion is exact.
inline glm::vec2 aoRandom(uint32_t pixel, uint32_t sample) {
  const uint32_t h1 = pcgHash(pixel ^ pcgHash(sample));
  const uint32_t h2 = pcgHash(h1);
  return glm::vec2(float(h1 >> 8u), float(h2 >> 8u)) * (1.0f / 16777216.0f);
}

// Cosine-distributed direction about the unit normal n (Duff et al. 2017's frame).
inline glm::vec3 aoDirection(glm::vec3 n, glm::vec2 u) {
  const float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 bt(b, sign + n.y * n.y * a, -n.y);
  const float r = std::sqrt(u.x);
  const float phi = 6.28318530718f * u.y;
  return t * (r * std::cos(phi)) + bt * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - u.x));
}

}  // namespace passtrace
