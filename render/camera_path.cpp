#include "render/camera_path.h"

#include <cmath>
#include <numbers>

namespace passtrace {

CameraSpec cameraPathView(const Scene& scene, int angle, int angles) {
  const Aabb box = scene.bounds();
  const glm::vec3 centre = box.empty() ? glm::vec3(0.0f) : box.center();
  const float radius = box.empty() ? 1.0f : std::max(0.5f * glm::length(box.extent()), 1e-6f);
  CameraSpec view = scene.camera;
  const float halfFov = glm::radians(view.fovDegrees) * 0.5f;
  const float distance = 1.05f * radius / std::sin(halfFov);
  const float t = 2.0f * std::numbers::pi_v<float> * float(angle) / float(angles);
  view.eye = centre + distance * glm::vec3(std::cos(t), std::sin(3.0f * t), std::sin(t));
  view.lookAt = centre;
  view.up = glm::vec3(0.0f, 1.0f, 0.0f);
  return view;
}

}  // namespace passtrace
