#include "stream/inout_stream.h"

#include <algorithm>
#include <string>

#include "stream/element_slots.h"
#include "stream/gl_error.h"
#include "stream/storage_buffer.h"

namespace passtrace {
namespace {

InOutStream* enabledStream = nullptr;  // as the GL's bound framebuffer: one per context
uint64_t storageBlockLimit = 0;        // limitStorageBlock(); 0: the driver's

}  // namespace

void InOutStream::checkSize(int width, int height) {
  GLint maxSize = 0, maxViewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
  const int limit = std::min({maxSize, maxViewport[0], maxViewport[1]});
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1 || width > limit || height > limit)
    throw GlError("stream size " + size + " is outside 1.." + std::to_string(limit) + " (the GL limit)");
}

InOutStream::InOutStream(int width, int height, int surfaceCount, StreamStage stage)
    : width_(width), height_(height), stage_(stage) {
  checkSize(width, height);
  // The compute stage stores each output location to an image unit.
  GLint maxOutputs = 0;
  glGetIntegerv(stage == StreamStage::Compute ? GL_MAX_IMAGE_UNITS : GL_MAX_DRAW_BUFFERS, &maxOutputs);
  if (surfaceCount < 1 || surfaceCount > kMaxSurfaces || surfaceCount > maxOutputs)
    throw GlError("a stream has 1.." + std::to_string(std::min(kMaxSurfaces, maxOutputs)) + " surfaces, not " +
                  std::to_string(surfaceCount));

  surfaces_.resize(surfaceCount);
  if (stage == StreamStage::Compute) {
    createSurfaceBuffer();
    active_ = std::make_unique<ActiveElements>(width, height);
    writeSurfaces_ = {0};
    checkGlError("creating a " + std::to_string(width) + "x" + std::to_string(height) + " compute-stage stream");
    return;
  }
  glCreateTextures(GL_TEXTURE_2D, surfaceCount, surfaces_.data());
  for (int i = 0; i < surfaceCount; ++i) {
    glTextureStorage2D(surfaces_[i], 1, GL_RGBA32F, width, height);
    glTextureParameteri(surfaces_[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(surfaces_[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateFramebuffers(1, &framebuffer_);
  for (int i = 0; i < surfaceCount; ++i)
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0 + i, surfaces_[i], 0);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
  glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
  setWriteSurfaces({0});
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  checkGlError("creating a " + size + " stream with " + std::to_string(surfaceCount) + " surfaces");
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04x", status);
    throw GlError("stream framebuffer " + size + " is incomplete (status " + hex + ")");
  }
}

void InOutStream::createSurfaceBuffer() {
  slots_ = passtrace::surfaceSlots(uint32_t(width_), uint32_t(height_));
  const uint64_t surfaceBytes = slots_ * sizeof(glm::vec4);
  const uint64_t bytes = surfaceBytes * surfaces_.size();
  GLint maxTexels = 0, alignment = 1;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const std::string size = std::to_string(width_) + "x" + std::to_string(height_);
  if (slots_ > uint64_t(maxTexels))
    throw GlError("a " + size + " compute-stage stream needs " + std::to_string(slots_) +
                  " texels per surface, past this driver's buffer textures (" + std::to_string(maxTexels) + ")");
  if (surfaceBytes % uint64_t(std::max(alignment, 1)) != 0)  // whole tiles: 1 KiB multiples
    throw GlError("this driver's buffer-texture alignment (" + std::to_string(alignment) + " bytes) splits a surface");
  const uint64_t blockLimit = storageBlockLimit != 0 ? storageBlockLimit : storageBlockLimitBytes();
  storesThroughImages_ = bytes > blockLimit;
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  checkGlError("allocating a " + size + " compute-stage stream (" + std::to_string(bytes >> 20) + " MiB)");
  glCreateTextures(GL_TEXTURE_BUFFER, GLsizei(surfaces_.size()), surfaces_.data());
  for (size_t k = 0; k < surfaces_.size(); ++k)
    glTextureBufferRange(surfaces_[k], GL_RGBA32F, buffer_, GLintptr(k * surfaceBytes), GLsizeiptr(surfaceBytes));
}

GLintptr InOutStream::surfaceOffset(int surface) const {
  (void)surfaces_.at(surface);  // throws std::out_of_range as the fragment stage's surfaces_.at does
  return GLintptr(uint64_t(surface) * slots_ * sizeof(glm::vec4));
}

void InOutStream::limitStorageBlock(uint64_t bytes) { storageBlockLimit = bytes; }

InOutStream::~InOutStream() {
  if (enabledStream == this) enabledStream = nullptr;
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(static_cast<GLsizei>(surfaces_.size()), surfaces_.data());
  glDeleteBuffers(1, &buffer_);
  glDeleteTextures(1, &depth_);
  if (savedDepth_ != 0) glDeleteTextures(1, &savedDepth_);
}

InOutStream* InOutStream::enabled() { return enabledStream; }

void InOutStream::enable() {
  enabledStream = this;
  if (stage_ == StreamStage::Compute) return;  // kernels store to images: no framebuffer
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
  if (rowLimit_ > 0 && rowLimit_ < height_) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, width_, rowLimit_);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
}

void InOutStream::disable() {
  if (enabledStream == this) enabledStream = nullptr;
  if (stage_ == StreamStage::Compute) return;
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void InOutStream::setWriteSurfaces(const std::vector<int>& surfaces) {
  if (surfaces == writeSurfaces_) return;
  if (stage_ == StreamStage::Compute) {  // StreamKernel binds the images per dispatch
    writeSurfaces_ = surfaces;
    return;
  }
  std::vector<GLenum> buffers;
  for (int s : surfaces) buffers.push_back(s == kNoSurface ? GL_NONE : GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(s));
  glNamedFramebufferDrawBuffers(framebuffer_, static_cast<GLsizei>(buffers.size()), buffers.data());
  writeSurfaces_ = surfaces;
}

void InOutStream::clearSurface(int surface, const glm::vec4& value) {
  if (buffer_ == 0) return glClearTexImage(surfaces_.at(surface), 0, GL_RGBA, GL_FLOAT, &value[0]);
  const GLsizeiptr bytes = GLsizeiptr(slots_ * sizeof(glm::vec4));
  glClearNamedBufferSubData(buffer_, GL_RGBA32F, surfaceOffset(surface), bytes, GL_RGBA, GL_FLOAT, &value[0]);
}

void InOutStream::clearDepth(float depth) {
  if (active_) return active_->reset(depth > 0.5f);  // kernels draw at 0.5 with GL_LESS
  glClearTexImage(depth_, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
}

void InOutStream::upload(int surface, const std::vector<glm::vec4>& texels) {
  if (texels.size() != elementCount()) throw GlError("upload: wrong element count for the stream");
  if (buffer_ == 0) {
    glTextureSubImage2D(surfaces_.at(surface), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, texels.data());
  } else {
    std::vector<glm::vec4> slots(slots_, glm::vec4(0.0f));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        slots[elementSlot(uint32_t(x), uint32_t(y), uint32_t(width_))] = texels[size_t(y) * size_t(width_) + size_t(x)];
    const GLsizeiptr bytes = GLsizeiptr(slots_ * sizeof(glm::vec4));
    glNamedBufferSubData(buffer_, surfaceOffset(surface), bytes, slots.data());
  }
  checkGlError("uploading a stream surface");
}

std::vector<glm::vec4> InOutStream::read(int surface) const {
  std::vector<glm::vec4> texels(elementCount());
  if (buffer_ == 0) {
    glGetTextureImage(surfaces_.at(surface), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
  } else {
    std::vector<glm::vec4> slots(slots_);
    const GLsizeiptr bytes = GLsizeiptr(slots_ * sizeof(glm::vec4));
    glGetNamedBufferSubData(buffer_, surfaceOffset(surface), bytes, slots.data());
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        texels[size_t(y) * size_t(width_) + size_t(x)] = slots[elementSlot(uint32_t(x), uint32_t(y), uint32_t(width_))];
  }
  checkGlError("reading a stream surface");
  return texels;
}

std::vector<float> InOutStream::readDepth() const {
  if (active_) return active_->read();
  std::vector<float> depth(elementCount());
  glGetTextureImage(depth_, 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(depth.size() * sizeof(float)),
                    depth.data());
  checkGlError("reading stream depth");
  return depth;
}

void InOutStream::saveDepth() {
  if (active_) return active_->save();
  if (savedDepth_ == 0) {
    glCreateTextures(GL_TEXTURE_2D, 1, &savedDepth_);
    glTextureStorage2D(savedDepth_, 1, GL_DEPTH_COMPONENT32F, width_, height_);
  }
  glCopyImageSubData(depth_, GL_TEXTURE_2D, 0, 0, 0, 0, savedDepth_, GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
  checkGlError("saving stream depth");
}

void InOutStream::restoreDepth() {
  if (active_) return active_->restore();
  if (savedDepth_ == 0) throw GlError("restoreDepth: no depth was saved");
  glCopyImageSubData(savedDepth_, GL_TEXTURE_2D, 0, 0, 0, 0, depth_, GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
  checkGlError("restoring stream depth");
}

}  // namespace passtrace
