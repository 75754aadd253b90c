#include "stream/stream_kernel.h"

#include <algorithm>

#include "stream/active_elements.h"
#include "stream/compute_variant.h"
#include "stream/const_input_stream.h"
#include "stream/gl_error.h"
#include "stream/gl_program.h"
#include "stream/inout_stream.h"
#include "stream/storage_buffer.h"

namespace passtrace {

StreamKernel::StreamKernel(std::string name, const std::string& glslFile, Depth depth,
                           const std::vector<std::string>& defines)
    : StreamKernel(std::move(name), glslFile, depth, currentStreamStage(), defines) {}

StreamKernel::StreamKernel(std::string name, const std::string& glslFile, Stage stage,
                           const std::vector<std::string>& defines)
    : StreamKernel(std::move(name), glslFile, Depth::Test, stage, defines) {}

StreamKernel::StreamKernel(std::string name, const std::string& glslFile, Depth depth, Stage stage,
                           const std::vector<std::string>& defines)
    : name_(std::move(name)), depth_(depth), stage_(stage) {
  if (stage_ == Stage::Fragment) {
    program_ = linkProgram(name_, "fullscreen_quad.vert", glslFile, defines);
    glCreateQueries(GL_SAMPLES_PASSED, 1, &query_);  // execute(true)'s fragment count
    glCreateVertexArrays(1, &vertexArray_);  // core profile draws need a VAO, even an empty one
  } else {
    program_ = linkComputeProgram(name_, glslFile, defines);
  }
  checkGlError("creating kernel " + name_);
}

StreamKernel::~StreamKernel() {
  glDeleteProgram(program_);
  glDeleteQueries(1, &query_);
  glDeleteVertexArrays(1, &vertexArray_);
}

GLint StreamKernel::location(const char* uniform) {
  auto it = locations_.find(uniform);
  if (it == locations_.end()) it = locations_.emplace(uniform, glGetUniformLocation(program_, uniform)).first;
  return it->second;  // -1 (ignored by GL) when the compiler removed an unused uniform
}

void StreamKernel::set(const char* u, float v) { glProgramUniform1f(program_, location(u), v); }
void StreamKernel::set(const char* u, int v) { glProgramUniform1i(program_, location(u), v); }
void StreamKernel::set(const char* u, uint32_t v) { glProgramUniform1ui(program_, location(u), v); }
void StreamKernel::set(const char* u, const glm::vec2& v) { glProgramUniform2f(program_, location(u), v.x, v.y); }
void StreamKernel::set(const char* u, const glm::vec3& v) {
  glProgramUniform3f(program_, location(u), v.x, v.y, v.z);
}
void StreamKernel::set(const char* u, const glm::vec4& v) {
  glProgramUniform4f(program_, location(u), v.x, v.y, v.z, v.w);
}

void StreamKernel::set(const char* u, const glm::ivec3& v) {
  glProgramUniform3i(program_, location(u), v.x, v.y, v.z);
}

void StreamKernel::bindTexture(const char* sampler, GLuint texture) {
  auto it = textures_.find(sampler);
  if (it == textures_.end()) {
    const GLuint unit = static_cast<GLuint>(textures_.size());
    it = textures_.emplace(sampler, std::make_pair(unit, texture)).first;
    glProgramUniform1i(program_, location(sampler), static_cast<GLint>(unit));
  }
  it->second.second = texture;
}

void StreamKernel::bindInput(const char* name, const ConstInputStream& stream) {
  // `name` is a ConstStream uniform (kernels_glsl/texel_address.glsl). Every
  // sampler slot the kernel was compiled with gets a texture: the pages,
  // then the last page again for slots the data does not need.
  const std::string base(name);
  const auto slot = [&](uint32_t i) { return base + ".pages[" + std::to_string(i) + "]"; };
  if (stream.pageCount() > 1 && location(slot(0).c_str()) != -1 && location(slot(stream.pageCount() - 1).c_str()) == -1)
    throw GlError("kernel " + name_ + ": " + base + " has " + std::to_string(stream.pageCount()) +
                  " texture pages but the kernel was compiled for fewer (STREAM_PAGES)");
  for (uint32_t i = 0; i < kMaxLargeStreamPages && (i == 0 || location(slot(i).c_str()) != -1); ++i)
    bindTexture(slot(i).c_str(), stream.texture(std::min(i, stream.pageCount() - 1)));
  set((base + ".widthLog2").c_str(), stream.widthLog2());
  set((base + ".pageLog2").c_str(), stream.pageLog2());
}

void StreamKernel::bindInput(const char* sampler, const InOutStream& stream, int surface) {
  if (stream.stage() != stage_)  // the stages keep surfaces differently (inout_stream.h)
    throw GlError("kernel " + name_ + ": " + sampler + " is a surface of a stream of the other stage");
  bindTexture(sampler, stream.surfaceTexture(surface));
}

void StreamKernel::bindStorage(GLuint binding, const StorageBuffer& buffer) { storage_[binding] = &buffer; }

void StreamKernel::bindOutput(GLuint location, const InOutStream& stream, int surface) {
  if (stream.stage() != Stage::Compute) throw GlError("kernel " + name_ + ": bindOutput() needs a compute-stage stream");
  if (!outputs_.empty() && outputStream_ != &stream)
    throw GlError("kernel " + name_ + ": dispatch() writes the surfaces of one stream");
  outputStream_ = &stream;
  outputs_[location] = surface;
}

void StreamKernel::bindResources() {
  glUseProgram(program_);
  for (const auto& [sampler, binding] : textures_) glBindTextureUnit(binding.first, binding.second);
  for (const auto& [binding, buffer] : storage_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer->buffer());
}

void StreamKernel::dispatch(int width, int height) {
  if (stage_ != Stage::Compute) throw GlError("kernel " + name_ + ": dispatch() needs Stage::Compute");
  if (outputStream_ && (outputStream_->width() != width || outputStream_->height() < height))
    throw GlError("kernel " + name_ + ": dispatch() covers elements of its output stream's width");
  bindResources();
  std::vector<int> writes(InOutStream::kMaxSurfaces, InOutStream::kNoSurface);
  for (const auto& [unit, surface] : outputs_) writes.at(unit) = surface;
  if (outputStream_) bindOutputs(*outputStream_, writes);
  if (!dispatchElements_ || dispatchElements_->width() != width || dispatchElements_->height() != height)
    dispatchElements_ = std::make_unique<ActiveElements>(width, height);
  dispatchElements_->reset(true);
  dispatchElements_->dispatch(program_, height, false, false);
  checkGlError("dispatching kernel " + name_);
}

// Output k of a compute-stage kernel goes to surface writes[k] of the
// stream (none where kNoSurface or past the list): its first slot in the
// stream's buffer, bound as one storage block, or the surface's image.
void StreamKernel::bindOutputs(const InOutStream& stream, const std::vector<int>& writes) {
  GLuint mask = 0;
  for (int k = 0; k < InOutStream::kMaxSurfaces; ++k) {
    const int surface = k < int(writes.size()) ? writes[size_t(k)] : InOutStream::kNoSurface;
    if (surface == InOutStream::kNoSurface) continue;
    mask |= 1u << k;
    const std::string slot = "uOutputSlot" + std::to_string(k) + "_";
    glProgramUniform1ui(program_, location(slot.c_str()), GLuint(uint64_t(surface) * stream.surfaceSlots()));
    if (stream.storesThroughImages())
      glBindImageTexture(GLuint(k), stream.surfaceTexture(surface), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kStreamSurfacesBinding, stream.surfaceBuffer());
  glProgramUniform1ui(program_, location("uStoreImages_"), stream.storesThroughImages() ? 1u : 0u);
  glProgramUniform1ui(program_, location("uWriteMask_"), mask);
}

// The compute stage: the outputs the stream's write surfaces name are
// stored to them, the elements the active ones.
uint64_t StreamKernel::executeCompute(bool countFragments) {
  InOutStream* stream = InOutStream::enabled();
  if (!stream || stream->stage() != Stage::Compute)
    throw GlError("kernel " + name_ + ": a compute-stage kernel runs on an enabled compute-stage stream");
  bindResources();
  // The cull kernel only retires elements (as its colour mask off does).
  bindOutputs(*stream, depth_ == Depth::Cull ? std::vector<int>{} : stream->writeSurfaces());
  const uint64_t count = stream->activeElements()->dispatch(program_, stream->rowsRun(),
                                                            depth_ == Depth::Cull, countFragments);
  checkGlError("executing kernel " + name_);
  return count;
}

uint64_t StreamKernel::execute(bool countFragments) {
  if (stage_ == Stage::Compute) return executeCompute(countFragments);
  if (InOutStream* stream = InOutStream::enabled(); stream && stream->stage() != Stage::Fragment)
    throw GlError("kernel " + name_ + ": a fragment-stage kernel runs on an enabled fragment-stage stream");
  bindResources();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // The cull kernel only retires elements; it must leave every surface as it is.
  const GLboolean colour = depth_ == Depth::Cull ? GL_FALSE : GL_TRUE;
  glColorMask(colour, colour, colour, colour);
  glDepthMask(depth_ == Depth::Cull ? GL_TRUE : GL_FALSE);
  glBindVertexArray(vertexArray_);
  if (countFragments) glBeginQuery(GL_SAMPLES_PASSED, query_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  if (countFragments) glEndQuery(GL_SAMPLES_PASSED);
  // Later passes read what this one wrote, possibly from the same surfaces.
  glTextureBarrier();
  // Storage-buffer writes are incoherent: without this barrier the next pass
  // may read a stale stack.
  if (!storage_.empty()) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  GLuint64 count = 0;
  if (countFragments) glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &count);
  checkGlError("executing kernel " + name_);
  return count;
}

}  // namespace passtrace
