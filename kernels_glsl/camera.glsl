// The camera contract of the README (render/camera.h computes the same):
// this fragment's primary ray direction. gl_FragCoord is the pixel centre,
// px + 0.5, py + 0.5 (row 0 the top row); py is the whole image's row.
#include "row_bands.glsl"

uniform vec3 uEye;
uniform vec3 uForward;
uniform vec3 uRight;
uniform vec3 uUp;          // up' = right x forward
uniform float uTanHalfFov;
uniform vec2 uResolution;  // width, height

vec3 cameraRayDirection() {
  float sx = (2.0 * gl_FragCoord.x / uResolution.x - 1.0) * uTanHalfFov * (uResolution.x / uResolution.y);
  float y = float(imageRow(uint(gl_FragCoord.y))) + 0.5;
  float sy = (1.0 - 2.0 * y / uResolution.y) * uTanHalfFov;
  vec3 d = uForward + sx * uRight + sy * uUp;
  return d / sqrt(dot(d, d));
}
