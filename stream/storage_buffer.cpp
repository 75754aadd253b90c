#include "stream/storage_buffer.h"

#include <algorithm>
#include <string_view>

#include "stream/gl_error.h"

namespace passtrace {

// llvmpipe reports 128 MiB, Mesa's default, yet addresses blocks up to 2 GiB
// (31-bit byte offsets): measured, a 2880^2 bvh-stack stream's 1.9 GiB of
// stacks gives the same hits as kk-bvh, and 3.5 GiB crash it. Other
// drivers: what they report.
uint64_t storageBlockLimitBytes() {
  GLint64 reported = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &reported);
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const bool llvmpipe = renderer && std::string_view(renderer).find("llvmpipe") != std::string_view::npos;
  const uint64_t limit = uint64_t(std::max<GLint64>(reported, 0));
  return llvmpipe ? std::max<uint64_t>(limit, (uint64_t(1) << 31) - 1) : limit;
}

namespace {

// A kernel binds the whole buffer as one block, and a block past the limit
// is undefined: llvmpipe crashes (a 4096^2 bvh-stack stream's 3.5 GiB of
// stacks). Say so instead.
void checkBlockSize(const std::string& what, uint64_t bytes) {
  const uint64_t limit = storageBlockLimitBytes();
  if (limit > 0 && bytes > limit)
    throw GlError(what + ": " + std::to_string(bytes >> 20) + " MiB exceed this driver's largest storage buffer (" +
                  std::to_string(limit >> 20) + " MiB); use a smaller image or the CPU renderer");
}

}  // namespace

StorageBuffer::StorageBuffer(std::string what) : what_(std::move(what)) {}

StorageBuffer::~StorageBuffer() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void StorageBuffer::reserve(uint64_t floats) {
  if (floats <= floats_) return;
  checkBlockSize(what_, floats * sizeof(float));
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
  checkBlockSize(what_, data.size() * sizeof(float));
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
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // kernels' storage writes, visible to the read-back
  if (!out.empty()) glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
  checkGlError("reading " + what_);
  return out;
}

}  // namespace passtrace
