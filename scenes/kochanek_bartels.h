#pragma once
// Kochanek–Bartels (TCB) splines for AFF animated transforms ("x name" with
// keyframes "k name"): Hermite segments whose tangents come from each key's
// tension, continuity and bias (Kochanek & Bartels 1984), with the tangents
// scaled for unevenly spaced key times. Before the first key and after the
// last the value is held; the ends use the end key as its own neighbour.

#include <vector>

#include <glm/glm.hpp>

namespace passtrace {

struct KbKey {
  float time = 0.0f;
  glm::vec4 value{0.0f};  // up to four interpolated components
  float tension = 0.0f;
  float continuity = 0.0f;
  float bias = 0.0f;
};

// Keys must be sorted by time (equal times allowed: the later key wins from
// that time on). An empty list gives zero.
glm::vec4 evaluateKochanekBartels(const std::vector<KbKey>& keys, float time);

// One AFF animated transform. Translation and scale keys hold x y z in
// value.xyz; rotation keys hold the axis in value.xyz and the angle in
// degrees in value.w. Rotations are interpolated as unit quaternions (each key
// is taken in the hemisphere of the previous one, components spline-
// interpolated, then renormalised), so an axis sign flip between keys does
// not spin the object round.
struct AnimatedTransform {
  std::vector<KbKey> translation, rotation, scale;
  // translate * rotate * scale at the given time; a missing block is identity.
  glm::mat4 at(float time) const;
};

}  // namespace passtrace
