#pragma once
// Bringing a scene of enormous or tiny coordinates into single precision's
// safe range.
//
// Why: the ray-triangle test (Möller–Trumbore) forms products of three
// lengths (t = (q·e2)/det with q ~ L², e2 ~ L), so a scene whose coordinates
// reach about 1e12 overflows float and one below about 1e-13 underflows;
// shading's ray offset and the framing camera square the extent (overflow
// near 1e19, underflow near 1e-19). Multiplying every coordinate by a power
// of two 2^k is exact in floating point, so the rescaled scene renders the
// same image, bit for bit, wherever nothing over- or underflowed, and hit
// distances scale back exactly by 2^-k.
//
// The rule: when the largest |vertex coordinate| M lies outside
// [2^kMinSafeExponent, 2^kMaxSafeExponent], vertices, camera eye and look-at
// and the light position are multiplied by 2^k with M·2^k in [1, 2), and
// Scene::scaleExponent records k. Scenes in range (every built-in one) are
// untouched.

#include "scenes/scene.h"

namespace passtrace {

inline constexpr int kMinSafeExponent = -16;  // 2^-16 ≈ 1.5e-5
inline constexpr int kMaxSafeExponent = 16;   // 2^16 = 65536

// The exponent k that normalizeSceneScale would apply (0 when in range or
// when every vertex is at the origin).
int sceneScaleExponent(const Scene& scene);

// Applies sceneScaleExponent: scales the scene by 2^k and adds k to
// scene.scaleExponent. Returns k.
int normalizeSceneScale(Scene& scene);

// x · 2^k, exact unless it over- or underflows.
glm::vec3 scaleByPowerOfTwo(const glm::vec3& x, int k);

}  // namespace passtrace
