#pragma once
// The lights a run shades with, chosen once the view is known.
//
// A file without lights gets framedLight(): above, in front of and to the
// right of its bounds. That lights an object seen from outside, but from
// inside a closed room (Conference, Sibenik) every point is then in shadow
// and the image is black. So a view whose eye lies inside the scene's bounds
// gets a light of its own: a headlight just above the eye (kHeadlightLift of
// the bounds' diagonal along the view's up vector), which lights whatever the
// camera sees from wherever it is, with short shadows that still show shape.
// Views from outside keep the framed light (and the images, hits and
// benchmarks measured with it).

#include <span>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace passtrace {

inline constexpr float kHeadlightLift = 0.01f;

// `given` (--light, in the file's units: rescaled by the scene's 2^k like
// --eye) replace the file's lights: each is white, divided by their number,
// and the thesis's one-light shading uses their sum at the first one's
// position (as for an AFF file with several `l` lines). Else a default light
// (Scene::lightIsDefault) seen from inside the bounds becomes the headlight.
// Throws std::runtime_error for a light that does not fit single precision.
void placeLights(Scene& scene, std::span<const glm::vec3> given, const CameraSpec& view);

}  // namespace passtrace
