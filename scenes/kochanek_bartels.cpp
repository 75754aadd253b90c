#include "scenes/kochanek_bartels.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace passtrace {

glm::vec4 evaluateKochanekBartels(const std::vector<KbKey>& keys, float time) {
  if (keys.empty()) return glm::vec4(0.0f);
  if (keys.size() == 1 || !(time > keys.front().time)) return keys.front().value;
  if (time >= keys.back().time) return keys.back().value;
  // The segment [i, i+1] holding time, with keys[i].time < keys[i+1].time.
  std::size_t i = 0;
  while (i + 1 < keys.size() && keys[i + 1].time <= time) ++i;
  const std::size_t n = keys.size();
  const KbKey& k0 = keys[i == 0 ? 0 : i - 1];
  const KbKey& k1 = keys[i];
  const KbKey& k2 = keys[i + 1];
  const KbKey& k3 = keys[std::min(i + 2, n - 1)];
  const float dt = k2.time - k1.time;  // > 0 by the search above
  const float dtBefore = i == 0 ? dt : k1.time - k0.time;
  const float dtAfter = i + 2 >= n ? dt : k3.time - k2.time;

  // Outgoing tangent at k1 and incoming tangent at k2.
  const glm::vec4 in1 = k1.value - k0.value, out1 = k2.value - k1.value;
  const glm::vec4 in2 = out1, out2 = k3.value - k2.value;
  const float t1 = k1.tension, c1 = k1.continuity, b1 = k1.bias;
  const float t2 = k2.tension, c2 = k2.continuity, b2 = k2.bias;
  glm::vec4 tangentOut = 0.5f * (1 - t1) * ((1 + c1) * (1 + b1) * in1 + (1 - c1) * (1 - b1) * out1);
  glm::vec4 tangentIn = 0.5f * (1 - t2) * ((1 - c2) * (1 + b2) * in2 + (1 + c2) * (1 - b2) * out2);
  // Uneven key spacing (Kochanek & Bartels, section 4).
  if (dtBefore + dt > 0.0f) tangentOut *= 2.0f * dt / (dtBefore + dt);
  if (dt + dtAfter > 0.0f) tangentIn *= 2.0f * dt / (dt + dtAfter);

  const float s = (time - k1.time) / dt;
  const float s2 = s * s, s3 = s2 * s;
  const float h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
  const float h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  return h00 * k1.value + h10 * tangentOut + h01 * k2.value + h11 * tangentIn;
}

glm::mat4 AnimatedTransform::at(float time) const {
  glm::mat4 m(1.0f);
  if (!translation.empty()) m = glm::translate(m, glm::vec3(evaluateKochanekBartels(translation, time)));
  if (!rotation.empty()) {
    std::vector<KbKey> quaternions = rotation;
    glm::vec4 previous(0.0f, 0.0f, 0.0f, 1.0f);
    for (KbKey& key : quaternions) {
      glm::vec3 axis(key.value);
      const float len = glm::length(axis);
      axis = len > 0.0f ? axis / len : glm::vec3(0.0f, 0.0f, 1.0f);
      const glm::quat q = glm::angleAxis(glm::radians(key.value.w), axis);
      glm::vec4 v(q.x, q.y, q.z, q.w);
      if (glm::dot(v, previous) < 0.0f) v = -v;
      key.value = previous = v;
    }
    glm::vec4 v = evaluateKochanekBartels(quaternions, time);
    const float len = glm::length(v);
    v = len > 0.0f ? v / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    m = m * glm::mat4_cast(glm::quat(v.w, v.x, v.y, v.z));
  }
  if (!scale.empty()) m = glm::scale(m, glm::vec3(evaluateKochanekBartels(scale, time)));
  return m;
}

}  // namespace passtrace
