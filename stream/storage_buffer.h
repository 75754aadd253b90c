#pragma once
// A shader storage buffer (GL 4.3+): per-element state a kernel reads and
// writes at any index and that outlives a pass, for state that does not fit
// the InOutStream's surfaces (a traversal's stack). Kernels declare it as
// `layout(std430, binding = B) buffer ...` and StreamKernel::bindStorage
// attaches it to binding B; StreamKernel::execute issues the memory barrier
// that makes one pass's writes visible to the next.

#include <cstdint>
#include <string>
#include <vector>

#include "stream/gl.h"

namespace passtrace {

// The largest storage block a kernel may bind, in bytes (0: unknown).
uint64_t storageBlockLimitBytes();

class StorageBuffer {
 public:
  // `what` names the data in error messages.
  explicit StorageBuffer(std::string what);
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;

  // Makes the buffer hold at least `floats` floats (all zero after growing). Throws GlError naming the data, e.g.
  // when out of GPU memory or past GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  void reserve(uint64_t floats);
  uint64_t floats() const { return floats_; }
  GLuint buffer() const { return buffer_; }

  // Replaces the contents with `data` (read-only for kernels after this), e.g. a tree's nodes. Throws as reserve.
  void upload(const std::vector<float>& data);
  // Sets the first `floats` floats to zero on the GPU (a counter a kernel then
  // increments, or per-element state before the buffer is reused).
  void zero(uint64_t floats);
  // The first `floats` floats, for tests.
  std::vector<float> read(uint64_t floats) const;

 private:
  std::string what_;
  GLuint buffer_ = 0;
  uint64_t floats_ = 0;
};

}  // namespace passtrace
