#pragma once
// What every loader promises about the Scene it returns and about the error
// it throws instead, checked by the fuzz targets (tests/fuzz/) and by the
// regression test over their findings (tests/unit/fuzz_regressions_test.cpp).

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "scenes/scene.h"

namespace passtrace::fuzz {

// Empty when the scene is usable by every renderer, else the first problem:
// finite materials, one material id per triangle, each naming a material; vertex normals
// absent or one triple per triangle; every coordinate finite.
inline std::string sceneProblem(const Scene& s) {
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (s.materials.empty()) return "no materials";
  for (std::size_t i = 0; i < s.materials.size(); ++i)
    if (!finite(s.materials[i].diffuse) || !finite(s.materials[i].mirror))
      return "material " + std::to_string(i) + " is not finite";
  if (s.materialIds.size() != s.triangles.size()) return "material ids and triangles differ in number";
  if (!s.vertexNormals.empty() && s.vertexNormals.size() != s.triangles.size())
    return "vertex normals and triangles differ in number";
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    if (s.materialIds[i] >= s.materials.size()) return "triangle " + std::to_string(i) + " names a missing material";
    const Triangle& t = s.triangles[i];
    if (!finite(t.v0) || !finite(t.v1) || !finite(t.v2)) return "triangle " + std::to_string(i) + " is not finite";
    if (!s.vertexNormals.empty())
      for (const glm::vec3& n : s.vertexNormals[i])
        if (!finite(n)) return "triangle " + std::to_string(i) + " has a non-finite normal";
  }
  const CameraSpec& c = s.camera;
  if (!finite(c.eye) || !finite(c.lookAt) || !finite(c.up) || !std::isfinite(c.fovDegrees))
    return "camera is not finite";
  if (!finite(s.light.position) || !finite(s.light.color) || !finite(s.background) || !std::isfinite(s.ambient))
    return "light, background or ambient is not finite";
  return {};
}

// Empty when `message` is a proper loader error about `file`: one line that
// starts with the file's name, or with the name of a file it includes (an
// AFF error lying in an included file names that file), and a reason.
inline std::string errorProblem(std::string_view message, const std::string& file) {
  if (message.find('\n') != std::string_view::npos || message.find('\r') != std::string_view::npos)
    return "error message spans lines";
  const std::size_t colon = message.find(':');
  if (colon == std::string_view::npos || colon + 2 >= message.size()) return "error message has no 'FILE: reason' form";
  const std::string named(message.substr(0, colon));
  std::error_code ignored;
  if (named != file && !std::filesystem::is_regular_file(named, ignored))
    return "error message does not start with the name of the file or of one it includes";
  return {};
}

}  // namespace passtrace::fuzz
