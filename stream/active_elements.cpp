#include "stream/active_elements.h"

#include <algorithm>
#include <bit>

#include "stream/compute_variant.h"
#include "stream/gl_error.h"
#include "stream/gl_program.h"

namespace passtrace {
namespace {

constexpr uint64_t kHeaderWords = 4;  // groups x, y, z; count
constexpr GLuint kMaxGroupsPerSide = 65535;  // the GL's guaranteed minimum

void setUniform(GLuint program, const char* name, GLuint value) {
  glProgramUniform1ui(program, glGetUniformLocation(program, name), value);
}

}  // namespace

ActiveElements::ActiveElements(int width, int height)
    : width_(width),
      height_(height),
      lists_{StorageBuffer("the compute stage's active elements"), StorageBuffer("the compute stage's active elements")},
      passed_("the compute stage's element count"),
      saved_("the compute stage's saved active elements") {
  const uint64_t words = kHeaderWords + uint64_t(width) * uint64_t(height);
  for (StorageBuffer& list : lists_) list.reserve(words);
  passed_.reserve(1);
  groupsProgram_ = linkComputeShader("active list groups", "active_list_groups.comp");
}

ActiveElements::~ActiveElements() { glDeleteProgram(groupsProgram_); }

void ActiveElements::reset(bool active) {
  all_ = active;
  if (!active) lists_[current_].zero(kHeaderWords);  // no groups, count 0
}

uint64_t ActiveElements::dispatch(unsigned program, int rows, bool cull, bool count) {
  StorageBuffer& in = lists_[current_];
  StorageBuffer& out = lists_[1 - current_];
  // A cull of every element covers the rows past the limit too: they stay
  // active, as the depth buffer keeps them (the fragment stage's scissor).
  const int covered = all_ && cull ? height_ : rows;
  glProgramUniform2ui(program, glGetUniformLocation(program, "uStreamSize_"), GLuint(width_), GLuint(covered));
  setUniform(program, "uRowsRun_", GLuint(rows));
  setUniform(program, "uElementList_", all_ ? 0u : 1u);
  setUniform(program, "uCull_", cull ? 1u : 0u);
  setUniform(program, "uCountPassed_", count ? 1u : 0u);
  if (cull) out.zero(kHeaderWords);
  if (count) passed_.zero(1);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kActiveListBinding, in.buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNextListBinding, out.buffer());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPassedCountBinding, passed_.buffer());
  if (all_) {
    // One group a tile: group g runs tile g (compute_variant.cpp).
    const GLuint groups = GLuint((width_ + kComputeTileSide - 1) / kComputeTileSide) *
                          GLuint((covered + kComputeTileSide - 1) / kComputeTileSide);
    const GLuint x = std::min(groups, kMaxGroupsPerSide);
    glDispatchCompute(x, (groups + x - 1) / x, 1);
  } else {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, in.buffer());
    glDispatchComputeIndirect(0);
  }
  // Later passes read the outputs as textures, storage as storage, the list as commands.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  if (cull) {
    glUseProgram(groupsProgram_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNextListBinding, out.buffer());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    current_ = 1 - current_;
    all_ = false;
  }
  checkGlError("dispatching a compute-stage kernel");
  return count ? std::bit_cast<uint32_t>(passed_.read(1).at(0)) : 0;
}

std::vector<float> ActiveElements::read() const {
  const size_t elements = size_t(width_) * size_t(height_);
  if (all_) return std::vector<float>(elements, 1.0f);
  const StorageBuffer& list = lists_[current_];
  const std::vector<float> words = list.read(kHeaderWords + elements);
  std::vector<float> active(elements, 0.0f);
  const uint32_t n = std::bit_cast<uint32_t>(words[3]);
  for (uint32_t i = 0; i < n; ++i) active.at(std::bit_cast<uint32_t>(words[kHeaderWords + i])) = 1.0f;
  return active;
}

void ActiveElements::save() {
  savedAll_ = all_;
  haveSaved_ = true;
  if (all_) return;
  saved_.reserve(lists_[current_].floats());
  glCopyNamedBufferSubData(lists_[current_].buffer(), saved_.buffer(), 0, 0,
                           GLsizeiptr(lists_[current_].floats() * sizeof(float)));
  checkGlError("saving the active elements");
}

void ActiveElements::restore() {
  if (!haveSaved_) throw GlError("restoreDepth: no depth was saved");
  all_ = savedAll_;
  if (all_) return;
  glCopyNamedBufferSubData(saved_.buffer(), lists_[current_].buffer(), 0, 0,
                           GLsizeiptr(lists_[current_].floats() * sizeof(float)));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  checkGlError("restoring the active elements");
}

}  // namespace passtrace
