#pragma once
// ConstInputStream (thesis 3.5): read-only data, such as a flattened
// acceleration structure, in an RGBA32F texture addressed as a 1-D array
// through texelOf() (stream/texel_address.h and kernels_glsl/texel_address.glsl).

#include <span>
#include <string>

#include <glm/glm.hpp>

#include "stream/gl.h"

namespace passtrace {

class ConstInputStream {
 public:
  // `what` names the data in error messages. Throws GlError if the texels do
  // not fit one texture of the GL's maximum size.
  ConstInputStream(std::span<const glm::vec4> texels, const std::string& what);
  ~ConstInputStream();
  ConstInputStream(const ConstInputStream&) = delete;
  ConstInputStream& operator=(const ConstInputStream&) = delete;

  GLuint texture() const { return texture_; }
  size_t size() const { return size_; }
  uint32_t widthLog2() const { return widthLog2_; }
  // The layout the constructor picks for `count` texels: the smallest
  // power-of-two width whose square holds them.
  static uint32_t chooseWidthLog2(size_t count);

 private:
  GLuint texture_ = 0;
  size_t size_ = 0;
  uint32_t widthLog2_ = 0;
};

}  // namespace passtrace
