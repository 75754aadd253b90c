#include "stream/inout_stream.h"

#include <algorithm>
#include <string>

#include "stream/gl_error.h"

namespace passtrace {
namespace {

InOutStream* enabledStream = nullptr;  // as the GL's bound framebuffer: one per context

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
  glCreateTextures(GL_TEXTURE_2D, surfaceCount, surfaces_.data());
  for (int i = 0; i < surfaceCount; ++i) {
    glTextureStorage2D(surfaces_[i], 1, GL_RGBA32F, width, height);
    glTextureParameteri(surfaces_[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(surfaces_[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  if (stage == StreamStage::Compute) {
    active_ = std::make_unique<ActiveElements>(width, height);
    writeSurfaces_ = {0};
    checkGlError("creating a " + std::to_string(width) + "x" + std::to_string(height) + " compute-stage stream");
    return;
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

InOutStream::~InOutStream() {
  if (enabledStream == this) enabledStream = nullptr;
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(static_cast<GLsizei>(surfaces_.size()), surfaces_.data());
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
  glClearTexImage(surfaces_.at(surface), 0, GL_RGBA, GL_FLOAT, &value[0]);
}

void InOutStream::clearDepth(float depth) {
  if (active_) return active_->reset(depth > 0.5f);  // kernels draw at 0.5 with GL_LESS
  glClearTexImage(depth_, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
}

void InOutStream::upload(int surface, const std::vector<glm::vec4>& texels) {
  if (texels.size() != elementCount()) throw GlError("upload: wrong element count for the stream");
  glTextureSubImage2D(surfaces_.at(surface), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, texels.data());
  checkGlError("uploading a stream surface");
}

std::vector<glm::vec4> InOutStream::read(int surface) const {
  std::vector<glm::vec4> texels(elementCount());
  glGetTextureImage(surfaces_.at(surface), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                    texels.data());
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
