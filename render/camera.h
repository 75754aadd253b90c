#pragma once
// The camera contract (README): pixel (px, py), py = 0 the top row, maps to
//   sx = (2(px+0.5)/W - 1) tan(fov/2) W/H,  sy = (1 - 2(py+0.5)/H) tan(fov/2)
//   direction = normalize(forward + sx right + sy up'), origin = eye,
// with forward = normalize(lookAt - eye), right = normalize(forward x up),
// up' = right x forward. kernels_glsl/raygen.frag computes the same.

#include <stdexcept>

#include "accel/geometry/geometry.h"
#include "scenes/scene.h"

namespace passtrace {

struct CameraBasis {
  glm::vec3 eye, forward, right, up;
  float tanHalfFov;
  int width, height;
};

// Throws std::invalid_argument for eye == lookAt, an up vector parallel to the
// view direction, a field of view outside (0, 180) or an empty image.
CameraBasis makeCameraBasis(const CameraSpec& camera, int width, int height);

Ray primaryRay(const CameraBasis& basis, int px, int py);

}  // namespace passtrace
