#pragma once
// ConstInputStream (thesis 3.5): read-only data, such as a flattened
// acceleration structure, as a 1-D array of RGBA32F texels addressed through
// texelOf() (stream/texel_address.h and kernels_glsl/texel_address.glsl).
//
// Data larger than one texture is split into pages: page p holds texels
// [p << pageLog2, (p + 1) << pageLog2), each page a texture of width
// 2^widthLog2. A GL caps a texture by side (GL_MAX_TEXTURE_SIZE) and may cap
// it by bytes too (llvmpipe refuses textures over 1 GiB, 2^26 RGBA32F texels),
// so the page size is the largest the GL accepts for a proxy texture. Kernels
// read a stream through the GLSL struct ConstStream, compiled with
// STREAM_PAGES (streamPagesDefine) sampler slots.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "stream/gl.h"

namespace passtrace {

// A kernel reads at most this many pages per stream (8 x 2^26 texels = 8 GiB
// on llvmpipe); three paged streams then still fit the 32 texture units.
inline constexpr uint32_t kMaxStreamPages = 8;
// ... and of its one large stream, if it declares one (LargeConstStream in
// kernels_glsl/texel_address.glsl; bvh-octant's sequences, 16 texels per
// triangle where its other streams have 1-4): 16 GiB on llvmpipe.
inline constexpr uint32_t kMaxLargeStreamPages = 16;

class ConstInputStream {
 public:
  // `what` names the data in error messages. `maxPageTexels` (rounded down to
  // a power of two; 0 = the largest texture the GL accepts) lets tests and
  // --page-texels exercise paging on small data. Throws GlError if the data
  // needs more than `maxPages` pages (kMaxLargeStreamPages for a kernel's
  // large stream) or the GL fails to store it (GL_OUT_OF_MEMORY is reported
  // as such).
  ConstInputStream(std::span<const glm::vec4> texels, const std::string& what, uint64_t maxPageTexels = 0,
                   uint32_t maxPages = kMaxStreamPages);
  // Storage for `count` texels, filled afterwards by write(): data made in
  // pieces (bvh-octant's eight sequences) goes up piece by piece, and the
  // whole never exists in memory beside the texture.
  ConstInputStream(size_t count, const std::string& what, uint64_t maxPageTexels = 0,
                   uint32_t maxPages = kMaxStreamPages);
  ~ConstInputStream();
  ConstInputStream(const ConstInputStream&) = delete;
  ConstInputStream& operator=(const ConstInputStream&) = delete;

  // Texels [first, first + texels.size()) of the stream (within size()).
  void write(size_t first, std::span<const glm::vec4> texels);

  size_t size() const { return size_; }
  uint32_t pageCount() const { return uint32_t(pages_.size()); }
  GLuint texture(uint32_t page = 0) const { return pages_.at(page); }
  uint32_t widthLog2() const { return widthLog2_; }
  // log2 of the texels per page; 31 for a single page (every valid index
  // then lies in page 0).
  uint32_t pageLog2() const { return pageLog2_; }

  // The single-page layout for `count` texels: the smallest power-of-two
  // width whose square holds them.
  static uint32_t chooseWidthLog2(size_t count);
  // log2 of the most RGBA32F texels one texture of this GL may hold.
  static uint32_t largestPageLog2();

 private:
  std::vector<GLuint> pages_;
  std::string what_;
  size_t size_ = 0;
  uint32_t widthLog2_ = 0;
  uint32_t pageLog2_ = 31;
};

// "STREAM_PAGES n" for a kernel that reads `streams`: n is the most pages any
// of them has (1 for data that fits one texture, so such kernels compile to
// a single plain texelFetch).
std::string streamPagesDefine(std::initializer_list<const ConstInputStream*> streams);
std::string streamPagesDefine(const std::vector<const ConstInputStream*>& streams);
// "LARGE_STREAM_PAGES n" for the kernel's one LargeConstStream.
std::string largeStreamPagesDefine(const ConstInputStream& stream);

}  // namespace passtrace
