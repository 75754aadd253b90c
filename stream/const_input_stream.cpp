#include "stream/const_input_stream.h"

#include <algorithm>
#include <bit>

#include "stream/gl_error.h"

namespace passtrace {
namespace {

// Does the GL accept an RGBA32F texture of this size? Proxy textures answer
// without allocating anything.
bool glAccepts(GLsizei width, GLsizei height) {
  glTexImage2D(GL_PROXY_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  GLint acceptedWidth = 0;
  glGetTexLevelParameteriv(GL_PROXY_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &acceptedWidth);
  return acceptedWidth != 0;
}

// One page: `texels` (all but possibly the last row full) into a new texture
// of 2^widthLog2 columns. Full rows go up straight from the caller's data;
// only a partial last row is copied, so no copy of the whole stream is made.
GLuint uploadPage(std::span<const glm::vec4> texels, uint32_t widthLog2, const std::string& what) {
  const size_t width = size_t(1) << widthLog2;
  const size_t fullRows = texels.size() / width;
  const size_t rows = std::max<size_t>(1, (texels.size() + width - 1) / width);
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, GLsizei(width), GLsizei(rows));
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  if (fullRows > 0)
    glTextureSubImage2D(texture, 0, 0, 0, GLsizei(width), GLsizei(fullRows), GL_RGBA, GL_FLOAT, texels.data());
  if (fullRows < rows) {
    std::vector<glm::vec4> last(width, glm::vec4(0.0f));
    std::copy(texels.begin() + fullRows * width, texels.end(), last.begin());
    glTextureSubImage2D(texture, 0, 0, GLint(fullRows), GLsizei(width), 1, GL_RGBA, GL_FLOAT, last.data());
  }
  try {
    checkGlError("uploading " + what + " (" + std::to_string(width * rows * sizeof(glm::vec4) >> 20) + " MiB texture)");
  } catch (...) {
    glDeleteTextures(1, &texture);
    throw;
  }
  return texture;
}

}  // namespace

uint32_t ConstInputStream::chooseWidthLog2(size_t count) {
  uint32_t log2 = 0;
  while ((size_t(1) << (2 * log2)) < count) ++log2;
  return log2;
}

uint32_t ConstInputStream::largestPageLog2() {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const uint32_t sideLog2 = uint32_t(std::bit_width(uint32_t(std::max(maxSize, 1)))) - 1;
  const GLsizei width = GLsizei(1) << sideLog2;
  uint32_t heightLog2 = sideLog2;
  while (heightLog2 > 0 && !glAccepts(width, GLsizei(1) << heightLog2)) --heightLog2;
  checkGlError("querying the largest texture");
  return sideLog2 + heightLog2;
}

ConstInputStream::ConstInputStream(std::span<const glm::vec4> texels, const std::string& what, uint64_t maxPageTexels)
    : size_(texels.size()) {
  uint32_t pageLog2 = largestPageLog2();
  if (maxPageTexels > 0) pageLog2 = std::min(pageLog2, uint32_t(std::bit_width(maxPageTexels)) - 1);
  const size_t pageTexels = size_t(1) << pageLog2;
  const size_t pages = std::max<size_t>(1, (size_ + pageTexels - 1) / pageTexels);
  if (pages > kMaxStreamPages)
    throw GlError(what + ": " + std::to_string(size_) + " texels need " + std::to_string(pages) +
                  " textures of " + std::to_string(pageTexels) + " texels; a kernel reads at most " +
                  std::to_string(kMaxStreamPages));
  if (pages == 1) {
    // As wide as high: the layout of a single texture since the thesis.
    widthLog2_ = chooseWidthLog2(std::max<size_t>(size_, 1));
    pageLog2_ = 31;
  } else {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    widthLog2_ = std::min(pageLog2, uint32_t(std::bit_width(uint32_t(maxSize))) - 1);
    pageLog2_ = pageLog2;
  }
  try {
    for (size_t p = 0; p < pages; ++p) {
      const size_t begin = p * pageTexels, end = std::min(size_, begin + pageTexels);
      const std::string page = pages == 1 ? what : what + " page " + std::to_string(p + 1) + "/" + std::to_string(pages);
      pages_.push_back(uploadPage(texels.subspan(std::min(begin, size_), end - std::min(begin, size_)), widthLog2_, page));
    }
  } catch (...) {
    glDeleteTextures(GLsizei(pages_.size()), pages_.data());
    throw;
  }
}

ConstInputStream::~ConstInputStream() { glDeleteTextures(GLsizei(pages_.size()), pages_.data()); }

std::string streamPagesDefine(std::initializer_list<const ConstInputStream*> streams) {
  return streamPagesDefine(std::vector<const ConstInputStream*>(streams));
}

std::string streamPagesDefine(const std::vector<const ConstInputStream*>& streams) {
  uint32_t pages = 1;
  for (const ConstInputStream* s : streams) pages = std::max(pages, s->pageCount());
  return "STREAM_PAGES " + std::to_string(pages);
}

}  // namespace passtrace
