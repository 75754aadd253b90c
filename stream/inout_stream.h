#pragma once
// InOutStream (thesis 3.5): one framebuffer holding up to 8 RGBA32F surfaces of
// width x height stream elements and a depth buffer that masks finished
// elements. Kernels read surfaces as textures and write others; which is
// which can change from pass to pass without re-creating anything. A kernel
// may read and write the same surface as long as each fragment reads only its
// own texel (GL 4.5 texture-barrier rules; StreamKernel issues the barrier).
//
// A stream made in the compute stage (stream/stream_stage.h) has no
// framebuffer: its surfaces are one buffer, surface after surface, each in
// tile order (stream/element_slots.h), which kernels read through buffer
// textures and store to as one storage block (or, past the largest block the
// driver allows, through image units). The active elements are an
// ActiveElements list instead of the depth buffer. Its depth calls keep
// their meaning (1 active, 0 finished); upload() and read() take and give
// elements in row order in both stages.

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "stream/active_elements.h"
#include "stream/gl.h"
#include "stream/stream_stage.h"

namespace passtrace {

class InOutStream {
 public:
  static constexpr int kMaxSurfaces = 8;

  // Throws GlError if the size is zero or beyond the GL limits, or the
  // framebuffer is incomplete. The stage is the current one (StreamStageScope).
  InOutStream(int width, int height, int surfaceCount, StreamStage stage = currentStreamStage());
  ~InOutStream();
  // Throws GlError unless a width x height stream fits the GL's limits.
  static void checkSize(int width, int height);
  InOutStream(const InOutStream&) = delete;
  InOutStream& operator=(const InOutStream&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int surfaceCount() const { return static_cast<int>(surfaces_.size()); }
  size_t elementCount() const { return size_t(width_) * size_t(height_); }
  StreamStage stage() const { return stage_; }

  // Binds the framebuffer and viewport: kernels executed until disable() write here.
  void enable();
  void disable();
  // The stream enable() was last called on (and not disabled), or null.
  static InOutStream* enabled();
  // Kernel output location k goes to surfaces[k]; kNoSurface drops it
  // (nothing is written for that output).
  static constexpr int kNoSurface = -1;
  void setWriteSurfaces(const std::vector<int>& surfaces);

  // Kernels executed after enable() run only on the first `rows` rows (a
  // scissor: llvmpipe then bins nothing beyond them); 0 = every row.
  void setRowLimit(int rows) { rowLimit_ = rows; }
  // The rows kernels run on: the row limit, or every row.
  int rowsRun() const { return rowLimit_ > 0 && rowLimit_ < height_ ? rowLimit_ : height_; }
  // The surface output location k goes to (setWriteSurfaces), or kNoSurface.
  const std::vector<int>& writeSurfaces() const { return writeSurfaces_; }
  // The compute stage's active elements (null in the fragment stage).
  ActiveElements* activeElements() { return active_.get(); }

  // The texture kernels read a surface through: 2-D in the fragment stage, a
  // buffer texture in the compute stage.
  GLuint surfaceTexture(int surface) const { return surfaces_.at(surface); }
  // Compute stage: the buffer holding every surface, surface k from slot
  // k * surfaceSlots(); whether kernels store to it through image units
  // rather than one storage block.
  GLuint surfaceBuffer() const { return buffer_; }
  uint64_t surfaceSlots() const { return slots_; }
  bool storesThroughImages() const { return storesThroughImages_; }
  // Compute-stage streams made afterwards store through a storage block only
  // when all their surfaces fit in `bytes` (0, the default: the driver's
  // largest block, storageBlockLimitBytes()). Tests lower it to run the
  // image path on small streams.
  static void limitStorageBlock(uint64_t bytes);

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
  void createSurfaceBuffer();  // the compute stage's surfaces
  GLintptr surfaceOffset(int surface) const;  // compute stage: where a surface starts in buffer_
  int width_, height_;
  StreamStage stage_;
  std::unique_ptr<ActiveElements> active_;  // compute stage only
  GLuint framebuffer_ = 0;
  GLuint depth_ = 0;
  GLuint savedDepth_ = 0;  // saveDepth()'s copy; 0 until first used
  std::vector<GLuint> surfaces_;  // textures (fragment) or buffer textures (compute)
  GLuint buffer_ = 0;             // compute stage: every surface, in tile order
  uint64_t slots_ = 0;            // compute stage: slots per surface
  bool storesThroughImages_ = false;
  std::vector<int> writeSurfaces_;
  int rowLimit_ = 0;
};

}  // namespace passtrace
