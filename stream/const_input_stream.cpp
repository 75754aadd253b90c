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

// One page of `texels` texels in 2^widthLog2 columns, the tail of its last
// row cleared to zero (never read, but defined).
GLuint allocatePage(size_t texels, uint32_t widthLog2, const std::string& what) {
  const size_t width = size_t(1) << widthLog2;
  const size_t rows = std::max<size_t>(1, (texels + width - 1) / width);
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, GLsizei(width), GLsizei(rows));
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  if (const size_t tail = rows * width - texels; tail > 0)
    glClearTexSubImage(texture, 0, GLint(width - tail), GLint(rows - 1), 0, GLsizei(tail), 1, 1, GL_RGBA, GL_FLOAT,
                       nullptr);
  try {
    checkGlError("making " + what + " (" + std::to_string(width * rows * sizeof(glm::vec4) >> 20) + " MiB texture)");
  } catch (...) {
    glDeleteTextures(1, &texture);
    throw;
  }
  return texture;
}

// Texels [first, first + texels.size()) of one page: a partial first row, full
// rows, a partial last row, each straight from the caller's data (no copy).
void writePage(GLuint texture, uint32_t widthLog2, size_t first, std::span<const glm::vec4> texels) {
  const size_t width = size_t(1) << widthLog2;
  while (!texels.empty()) {
    const size_t x = first % width, y = first / width;
    const size_t rows = x == 0 ? std::max<size_t>(1, texels.size() / width) : 1;
    const size_t count = x == 0 && texels.size() >= width ? rows * width : std::min(width - x, texels.size());
    glTextureSubImage2D(texture, 0, GLint(x), GLint(y), GLsizei(rows > 1 || count == width ? width : count),
                        GLsizei(rows), GL_RGBA, GL_FLOAT, texels.data());
    first += count;
    texels = texels.subspan(count);
  }
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

ConstInputStream::ConstInputStream(std::span<const glm::vec4> texels, const std::string& what, uint64_t maxPageTexels,
                                   uint32_t maxPages)
    : ConstInputStream(texels.size(), what, maxPageTexels, maxPages) {
  write(0, texels);  // a throw here runs the destructor: the delegated constructor has finished
}

ConstInputStream::ConstInputStream(size_t count, const std::string& what, uint64_t maxPageTexels, uint32_t maxPages)
    : what_(what), size_(count) {
  uint32_t pageLog2 = largestPageLog2();
  if (maxPageTexels > 0) pageLog2 = std::min(pageLog2, uint32_t(std::bit_width(maxPageTexels)) - 1);
  const size_t pageTexels = size_t(1) << pageLog2;
  const size_t pages = std::max<size_t>(1, (size_ + pageTexels - 1) / pageTexels);
  if (pages > maxPages)
    throw GlError(what + ": " + std::to_string(size_) + " texels need " + std::to_string(pages) +
                  " textures of " + std::to_string(pageTexels) + " texels; a kernel reads at most " +
                  std::to_string(maxPages));
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
      const size_t begin = std::min(size_, p * pageTexels), end = std::min(size_, begin + pageTexels);
      const std::string page = pages == 1 ? what : what + " page " + std::to_string(p + 1) + "/" + std::to_string(pages);
      pages_.push_back(allocatePage(end - begin, widthLog2_, page));
    }
  } catch (...) {
    glDeleteTextures(GLsizei(pages_.size()), pages_.data());
    throw;
  }
}

void ConstInputStream::write(size_t first, std::span<const glm::vec4> texels) {
  if (first > size_ || texels.size() > size_ - first)
    throw GlError(what_ + ": writing texels " + std::to_string(first) + "-" + std::to_string(first + texels.size()) +
                  " of " + std::to_string(size_));
  const size_t pageTexels = pageLog2_ >= 31 ? size_ + 1 : size_t(1) << pageLog2_;
  while (!texels.empty()) {
    const size_t page = first / pageTexels, offset = first % pageTexels;
    const size_t count = std::min(texels.size(), pageTexels - offset);
    writePage(pages_[page], widthLog2_, offset, texels.first(count));
    first += count;
    texels = texels.subspan(count);
  }
  checkGlError("uploading " + what_);
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

std::string largeStreamPagesDefine(const ConstInputStream& stream) {
  return "LARGE_STREAM_PAGES " + std::to_string(stream.pageCount());
}

}  // namespace passtrace
