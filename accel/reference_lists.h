#pragma once
// Triangle reference lists as the GPU reads them (thesis figure 12), shared by
// the kd-trees and the uniform grid: one float per entry, a packed triangle
// index (stream/texel_address.h), each list ended by kListEnd; four entries
// per RGBA texel, so entry j is channel j & 3 of texel j >> 2
// (kernels_glsl/reference_lists.glsl).

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "stream/texel_address.h"

namespace passtrace {

inline constexpr float kListEnd = -1.0f;  // packed indices are positive

class ReferenceLists {
 public:
  // Appends a list and returns the entry index of its first element.
  uint32_t append(std::span<const uint32_t> triangles) {
    const auto start = static_cast<uint32_t>(entries_.size());
    for (uint32_t t : triangles) entries_.push_back(packIndex(t));
    entries_.push_back(kListEnd);
    return start;
  }
  const std::vector<float>& entries() const { return entries_; }
  // Entries padded with kListEnd to whole texels.
  std::vector<glm::vec4> texels() const {
    std::vector<glm::vec4> out((entries_.size() + 3) / 4, glm::vec4(kListEnd));
    for (size_t j = 0; j < entries_.size(); ++j) out[j / 4][int(j % 4)] = entries_[j];
    return out;
  }

 private:
  std::vector<float> entries_;
};

// The triangles themselves for list-based structures: 3 texels per triangle
// in scene order, (v0, 0) (v1, 0) (v2, 0).
inline std::vector<glm::vec4> triangleVertexTexels(std::span<const Triangle> tris) {
  std::vector<glm::vec4> out;
  out.reserve(3 * tris.size());
  for (const Triangle& t : tris) {
    out.emplace_back(t.v0, 0.0f);
    out.emplace_back(t.v1, 0.0f);
    out.emplace_back(t.v2, 0.0f);
  }
  return out;
}

}  // namespace passtrace
