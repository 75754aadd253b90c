#include "scenes/scene_lights.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/scene_scale.h"

namespace passtrace {
namespace {

bool strictlyInside(const Aabb& box, const glm::vec3& p) {
  return glm::all(glm::greaterThan(p, box.min)) && glm::all(glm::lessThan(p, box.max));
}

}  // namespace

void placeLights(Scene& scene, std::span<const glm::vec3> given, const CameraSpec& view) {
  if (!given.empty()) {
    const glm::vec3 color(1.0f / float(given.size()));
    scene.lights.clear();
    for (const glm::vec3& p : given) {
      const glm::vec3 position = scaleByPowerOfTwo(p, scene.scaleExponent);
      if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
        throw std::runtime_error("--light: too far from the scene for single precision (the scene is rescaled by 2^" +
                                 std::to_string(scene.scaleExponent) + ")");
      scene.lights.push_back({position, color});
    }
    scene.light = {scene.lights.front().position, glm::vec3(1.0f)};
    if (scene.lights.size() == 1) scene.lights.clear();  // `light` alone says it all
    scene.lightIsDefault = false;
    return;
  }
  const Aabb box = scene.bounds();
  if (!scene.lightIsDefault || !strictlyInside(box, view.eye)) return;
  const glm::vec3 up = glm::length(view.up) > 0.0f ? glm::normalize(view.up) : glm::vec3(0, 1, 0);
  scene.light.position = view.eye + up * (kHeadlightLift * glm::length(box.max - box.min));
}

}  // namespace passtrace
