#pragma once
// InOutStream (thesis 3.5): one framebuffer holding up to 8 RGBA32F surfaces of
// width x height stream elements and a depth buffer that masks finished
// elements. Kernels read surfaces as textures and write others; which is
// which can change from pass to pass without re-creating anything. A kernel
// may read and write the same surface as long as each fragment reads only its
// own texel (GL 4.5 texture-barrier rules; StreamKernel issues the barrier).

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "stream/gl.h"

namespace passtrace {

class InOutStream {
 public:
  static constexpr int kMaxSurfaces = 8;

  // Throws GlError if the size is zero or beyond the GL limits, or the
  // framebuffer is incomplete.
  InOutStream(int width, int height, int surfaceCount);
  ~InOutStream();
  // Throws GlError unless a width x height stream fits the GL's limits.
  static void checkSize(int width, int height);
  InOutStream(const InOutStream&) = delete;
  InOutStream& operator=(const InOutStream&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int surfaceCount() const { return static_cast<int>(surfaces_.size()); }
  size_t elementCount() const { return size_t(width_) * size_t(height_); }

  // Binds the framebuffer and viewport: kernels executed until disable() write here.
  void enable();
  void disable();
  // Kernel output location k goes to surfaces[k]; kNoSurface drops it
  // (nothing is written for that output).
  static constexpr int kNoSurface = -1;
  void setWriteSurfaces(const std::vector<int>& surfaces);

  // Kernels executed after enable() run only on the first `rows` rows (a
  // scissor: llvmpipe then bins nothing beyond them); 0 = every row.
  void setRowLimit(int rows) { rowLimit_ = rows; }

  GLuint surfaceTexture(int surface) const { return surfaces_.at(surface); }

  void clearSurface(int surface, const glm::vec4& value);
  // Depth 1 marks an element active, 0 finished (kernels draw at depth 0.5 with GL_LESS).
  void clearDepth(float depth);

  // Element (x, y) is texel (x, y): row 0 is the first row in memory.
  void upload(int surface, const std::vector<glm::vec4>& texels);
  std::vector<glm::vec4> read(int surface) const;
  std::vector<float> readDepth() const;

  // Two structures traced one after the other over the same rays (--dynamic
  // two-trees): the first one's cull retires every ray it finishes, so the
  // depth buffer (which rays are active) is saved before it and restored
  // before the second. A GPU-side copy into a second depth texture, made on
  // first use.
  void saveDepth();
  void restoreDepth();

 private:
  int width_, height_;
  GLuint framebuffer_ = 0;
  GLuint depth_ = 0;
  GLuint savedDepth_ = 0;  // saveDepth()'s copy; 0 until first used
  std::vector<GLuint> surfaces_;
  std::vector<int> writeSurfaces_;
  int rowLimit_ = 0;
};

}  // namespace passtrace
