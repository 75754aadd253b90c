#include "stream/storage_buffer.h"

#include <algorithm>

#include "stream/gl_error.h"

namespace passtrace {

StorageBuffer::StorageBuffer(std::string what) : what_(std::move(what)) {}

StorageBuffer::~StorageBuffer() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void StorageBuffer::reserve(uint64_t floats) {
  if (floats <= floats_) return;
  if (buffer_) glDeleteBuffers(1, &buffer_);
  buffer_ = 0;
  floats_ = 0;
  glCreateBuffers(1, &buffer_);
  // Immutable storage: the size is fixed, the kernels write it (no client access).
  glNamedBufferStorage(buffer_, GLsizeiptr(floats * sizeof(float)), nullptr, 0);
  const float zero = 0.0f;
  glClearNamedBufferData(buffer_, GL_R32F, GL_RED, GL_FLOAT, &zero);
  checkGlError("allocating " + what_ + " (" + std::to_string((floats * sizeof(float)) >> 20) + " MiB storage buffer)");
  floats_ = floats;
}

void StorageBuffer::zero(uint64_t floats) {
  if (!buffer_) return;
  const float zero = 0.0f;
  const GLsizeiptr bytes = GLsizeiptr(std::min(floats, floats_) * sizeof(float));
  glClearNamedBufferSubData(buffer_, GL_R32F, 0, bytes, GL_RED, GL_FLOAT, &zero);
  checkGlError("clearing " + what_);
}

void StorageBuffer::upload(const std::vector<float>& data) {
  if (buffer_) glDeleteBuffers(1, &buffer_);
  buffer_ = 0;
  floats_ = 0;
  glCreateBuffers(1, &buffer_);
  const float none = 0.0f;  // a zero-sized buffer cannot be bound: keep one float
  glNamedBufferStorage(buffer_, GLsizeiptr(std::max<size_t>(data.size(), 1) * sizeof(float)),
                       data.empty() ? &none : data.data(), 0);
  checkGlError("uploading " + what_ + " (" + std::to_string((data.size() * sizeof(float)) >> 20) + " MiB storage buffer)");
  floats_ = std::max<size_t>(data.size(), 1);
}

std::vector<float> StorageBuffer::read(uint64_t floats) const {
  std::vector<float> out(std::min(floats, floats_));
  if (!out.empty()) glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
  checkGlError("reading " + what_);
  return out;
}

}  // namespace passtrace
