#pragma once
// StreamKernel (thesis 3.5): a GLSL fragment program from kernels_glsl/, its
// uniforms and its input streams. execute() draws one full-screen quad into
// the enabled InOutStream; elements whose depth marks them finished fail the
// early depth test and never run. With countFragments it returns the
// occlusion-query count of fragments that passed the depth test and were not
// discarded.
//
// In the compute stage (stream/stream_stage.h) the same file is built as a
// compute shader (compute_variant.h), and execute() runs it over the enabled
// stream's active elements (stream/active_elements.h) with the same meaning:
// the same elements run, write the same surfaces, and are counted alike.
// dispatch() runs a compute-stage kernel over every element of a size, with
// the outputs bindOutput() named, outside any stream (measurements).

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "stream/gl.h"
#include "stream/stream_stage.h"

namespace passtrace {

class ActiveElements;
class ConstInputStream;
class InOutStream;
class StorageBuffer;

class StreamKernel {
 public:
  enum class Depth {
    Test,  // compute kernels: run only where the element is active, never write depth
    Cull   // the cull kernel: writes gl_FragDepth to retire finished elements
  };

  // Compiles and links `glslFile` (a kernels_glsl/ file) with the shared quad
  // vertex program, or as a compute shader, in the current stage. Throws
  // GlError naming the kernel, file, line and the driver's log on failure.
  StreamKernel(std::string name, const std::string& glslFile, Depth depth = Depth::Test,
               const std::vector<std::string>& defines = {});
  using Stage = StreamStage;
  // In the stage given.
  StreamKernel(std::string name, const std::string& glslFile, Stage stage,
               const std::vector<std::string>& defines = {});
  ~StreamKernel();
  StreamKernel(const StreamKernel&) = delete;
  StreamKernel& operator=(const StreamKernel&) = delete;

  const std::string& name() const { return name_; }

  void set(const char* uniform, float v);
  void set(const char* uniform, int v);
  void set(const char* uniform, uint32_t v);
  void set(const char* uniform, const glm::vec2& v);
  void set(const char* uniform, const glm::vec3& v);
  void set(const char* uniform, const glm::vec4& v);
  void set(const char* uniform, const glm::ivec3& v);

  // Binds a ConstStream uniform (its page samplers and layout) to constant
  // data, or a sampler2D uniform to one surface of a stream.
  void bindInput(const char* name, const ConstInputStream& stream);
  void bindInput(const char* sampler, const InOutStream& stream, int surface);
  // Attaches a storage buffer to the kernel's `layout(binding = binding)`
  // buffer block; kept until bound again. The buffer must outlive the kernel's
  // executions.
  void bindStorage(GLuint binding, const StorageBuffer& buffer);

  // Runs the kernel over the active elements of the enabled stream, which
  // must be of the kernel's stage. With countFragments, returns how many
  // of them did not discard (the fragment stage's occlusion query).
  uint64_t execute(bool countFragments = false);

  // Stage::Compute only: the surface that `layout(location = location) out`
  // writes; kept until bound again.
  void bindOutput(GLuint location, const InOutStream& stream, int surface);
  // Stage::Compute only: runs the kernel over width x height elements.
  void dispatch(int width, int height);
  StreamStage stage() const { return stage_; }

 private:
  StreamKernel(std::string name, const std::string& glslFile, Depth depth, Stage stage,
               const std::vector<std::string>& defines);
  GLint location(const char* uniform);
  void bindTexture(const char* sampler, GLuint texture);

  void bindResources();
  uint64_t executeCompute(bool countFragments);
  void bindOutputs(const InOutStream& stream, const std::vector<int>& writes);

  std::string name_;
  Depth depth_;
  Stage stage_ = Stage::Fragment;
  GLuint program_ = 0;
  GLuint query_ = 0;
  GLuint vertexArray_ = 0;
  std::map<std::string, GLint> locations_;
  std::map<std::string, std::pair<GLuint, GLuint>> textures_;  // sampler -> (unit, texture)
  std::map<GLuint, const StorageBuffer*> storage_;             // binding point -> buffer
  std::map<GLuint, int> outputs_;                              // dispatch(): output location -> surface
  const InOutStream* outputStream_ = nullptr;                  // dispatch(): whose surfaces
  std::unique_ptr<ActiveElements> dispatchElements_;            // dispatch()'s every-element list
};

}  // namespace passtrace
