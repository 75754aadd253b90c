#pragma once
// The camera contract (README): pixel (px, py), py = 0 the top row, maps to
//   sx = (2(px+0.5)/W - 1) tan(fov/2) W/H,  sy = (1 - 2(py+0.5)/H) tan(fov/2)
//   direction = normalize(forward + sx right + sy up'), origin = eye,
// with forward = normalize(lookAt - eye), right = normalize(forward x up),
// up' = right x forward. kernels_glsl/raygen.frag computes the same.

#include <cmath>
#include <stdexcept>

#include "accel/geometry/geometry.h"
#include "render/row_bands.h"
#include "scenes/scene.h"

namespace passtrace {

struct CameraBasis {
  glm::vec3 eye, forward, right, up;
  float tanHalfFov;
  int width, height;  // the whole image's
  RowBands rows;      // the rows traced (an MPI rank's); py is a local row
};

// Throws std::invalid_argument for eye == lookAt, an up vector parallel to the
// view direction, a field of view outside (0, 180) or an empty image.
// `height` is the image traced: the whole one, or `rows`' local rows.
CameraBasis makeCameraBasis(const CameraSpec& camera, int width, int height, const RowBands& rows = {});

// Pixel (px, py)'s direction, in three steps so that a tile can compute sx
// once per column and sy once per row. Inline: renderers call these per
// pixel, and a call returned the ray through memory, whose reload stalled
// on store forwarding. Written as raygen.frag writes it, so both round alike.
inline float cameraScreenX(const CameraBasis& b, int px) {
  const float w = float(b.width), h = float(b.height);
  return (2.0f * (float(px) + 0.5f) / w - 1.0f) * b.tanHalfFov * (w / h);
}
inline float cameraScreenY(const CameraBasis& b, int py) {
  py = b.rows.globalRow(py);
  return (1.0f - 2.0f * (float(py) + 0.5f) / float(b.height)) * b.tanHalfFov;
}
inline glm::vec3 cameraDirection(const CameraBasis& b, float sx, float sy) {
  const glm::vec3 d = b.forward + sx * b.right + sy * b.up;
  return d / std::sqrt(glm::dot(d, d));
}
// cameraDirection for kLanes pixels of one row at once, as x, y, z arrays:
// the same operations lane by lane (IEEE square root and division round
// alike in every lane), written so that the compiler vectorises them.
template <int kLanes>
inline void cameraDirections(const CameraBasis& b, const float (&sx)[kLanes], float sy, float (&x)[kLanes],
                             float (&y)[kLanes], float (&z)[kLanes]) {
  for (int k = 0; k < kLanes; ++k) {
    x[k] = b.forward.x + sx[k] * b.right.x + sy * b.up.x;
    y[k] = b.forward.y + sx[k] * b.right.y + sy * b.up.y;
    z[k] = b.forward.z + sx[k] * b.right.z + sy * b.up.z;
  }
  for (int k = 0; k < kLanes; ++k) {
    const float length = std::sqrt(x[k] * x[k] + y[k] * y[k] + z[k] * z[k]);
    x[k] /= length, y[k] /= length, z[k] /= length;
  }
}
inline Ray primaryRay(const CameraBasis& b, int px, int py) {
  return Ray{b.eye, cameraDirection(b, cameraScreenX(b, px), cameraScreenY(b, py)), kInfinity};
}

}  // namespace passtrace
