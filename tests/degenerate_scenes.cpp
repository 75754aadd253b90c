#include "tests/degenerate_scenes.h"

#include <cmath>
#include <cstdio>

#include "scenes/scene_scale.h"

namespace passtrace::test {

std::string objOf(const std::vector<Triangle>& tris) {
  std::string text;
  char line[160];
  for (const Triangle& t : tris)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", double(v.x), double(v.y), double(v.z));
      text += line;
    }
  for (size_t i = 0; i < tris.size(); ++i) text += "f " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
  return text;
}

std::vector<Triangle> heightField(int n, bool bumpy) {
  const auto at = [&](int i, int j) {
    const float x = -1.0f + 2.0f * float(i) / float(n), y = -1.0f + 2.0f * float(j) / float(n);
    return glm::vec3(x, y, bumpy ? 0.3f * std::sin(3.0f * x) * std::cos(2.0f * y) : 0.0f);
  };
  std::vector<Triangle> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      tris.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return tris;
}

std::vector<Triangle> transformed(std::vector<Triangle> tris, const std::function<glm::vec3(glm::vec3)>& f) {
  for (Triangle& t : tris) t = {f(t.v0), f(t.v1), f(t.v2)};
  return tris;
}

std::vector<Triangle> scaledByPowerOfTwo(std::vector<Triangle> tris, int k) {
  return transformed(std::move(tris), [k](glm::vec3 v) { return scaleByPowerOfTwo(v, k); });
}

}  // namespace passtrace::test
