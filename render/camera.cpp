#include "render/camera.h"

#include <cmath>
#include <string>

namespace passtrace {

CameraBasis makeCameraBasis(const CameraSpec& camera, int width, int height, const RowBands& rows) {
  if (width < 1 || height < 1) throw std::invalid_argument("image size must be at least 1x1");
  if (!rows.whole() && rows.localHeight() != height)
    throw std::invalid_argument("an image of " + std::to_string(height) + " rows for a band of " +
                                std::to_string(rows.localHeight()));
  if (!(camera.fovDegrees > 0.0f && camera.fovDegrees < 180.0f))
    throw std::invalid_argument("field of view must be between 0 and 180 degrees");
  const glm::vec3 view = camera.lookAt - camera.eye;
  if (!(glm::dot(view, view) > 0.0f)) throw std::invalid_argument("camera eye and look-at point coincide");
  const glm::vec3 forward = glm::normalize(view);
  const glm::vec3 side = glm::cross(forward, camera.up);
  if (!(glm::length(side) > 1e-6f * glm::length(camera.up)))
    throw std::invalid_argument("camera up vector is zero or parallel to the view direction");
  const glm::vec3 right = glm::normalize(side);
  return CameraBasis{camera.eye, forward, right, glm::cross(right, forward),
                     std::tan(glm::radians(camera.fovDegrees) * 0.5f), width, rows.whole() ? height : rows.fullHeight,
                     rows};
}

}  // namespace passtrace
