#include "stream/const_input_stream.h"

#include <algorithm>
#include <vector>

#include "stream/gl_error.h"

namespace passtrace {

uint32_t ConstInputStream::chooseWidthLog2(size_t count) {
  uint32_t log2 = 0;
  while ((size_t(1) << (2 * log2)) < count) ++log2;
  return log2;
}

ConstInputStream::ConstInputStream(std::span<const glm::vec4> texels, const std::string& what)
    : size_(texels.size()) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  widthLog2_ = chooseWidthLog2(std::max<size_t>(size_, 1));
  const size_t width = size_t(1) << widthLog2_;
  const size_t height = std::max<size_t>(1, (size_ + width - 1) / width);
  if (width > size_t(maxSize) || height > size_t(maxSize))
    throw GlError(what + ": " + std::to_string(size_) + " texels do not fit one " + std::to_string(maxSize) + "x" +
                  std::to_string(maxSize) + " texture");
  // Pad the last row so one upload fills the whole texture.
  std::vector<glm::vec4> padded(width * height, glm::vec4(0.0f));
  std::copy(texels.begin(), texels.end(), padded.begin());
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, 1, GL_RGBA32F, GLsizei(width), GLsizei(height));
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureSubImage2D(texture_, 0, 0, 0, GLsizei(width), GLsizei(height), GL_RGBA, GL_FLOAT, padded.data());
  checkGlError("uploading " + what);
}

ConstInputStream::~ConstInputStream() { glDeleteTextures(1, &texture_); }

}  // namespace passtrace
