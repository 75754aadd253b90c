#pragma once
// The measurement tools' SCENE argument: a scene name or path as passtrace's
// -s takes it, or "spheres:N" for the spheres scene of at least N triangles
// (passtrace's -s spheres --triangles N; the scaling benchmark's sizes).

#include <string>

#include "scenes/scene_registry.h"
#include "tests/measure/renderer_rays.h"

namespace passtrace {

inline Scene loadToolScene(const std::string& argument) {
  const std::string spheres = "spheres:";
  if (argument.rfind(spheres, 0) != 0) return loadScene(argument);
  SceneOptions options;
  options.triangles = uint64_t(parsePositiveInt("SCENE's triangle count", argument.c_str() + spheres.size()));
  return loadScene("spheres", options);
}

}  // namespace passtrace
