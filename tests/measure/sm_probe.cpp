// Issue 38: on which of the GPU's streaming multiprocessors (SMs) does each
// stage of the stream layer run? The probe kernel (kernels_glsl/sm_probe.frag)
// counts its elements per SM id (GL_NV_shader_thread_group's gl_SMIDNV) once
// as a fragment pass and once in the compute stage (stream/stream_stage.h),
// over a WIDTH x WIDTH stream, so the report can state rates per SM that each
// stage could use instead of per GPU. Prints one JSON line: the driver's
// GL_SM_COUNT_NV (null where the query fails), and per stage the SM ids seen,
// how many, the elements and the pass's time (glFinish, steady clock, after
// a warm-up). Where the extension is missing (llvmpipe, other vendors) it
// says so ("shader_thread_group": false) and exits 0.
//
//   build/tests/measure/measure_sm_probe [WIDTH=2048]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stream/gl_context.h"
#include "stream/inout_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace {

using namespace passtrace;

constexpr GLenum kSmCountNv = 0x933B;  // GL_SM_COUNT_NV (GL_NV_shader_thread_group); not in glad's core table
constexpr uint32_t kMaxSmIds = 1024;

bool hasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::string(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) == name) return true;
  return false;
}

nlohmann::json probe(StreamStage stage, int width) {
  const StreamStageScope scope(stage);
  InOutStream stream(width, width, 1);
  StreamKernel kernel("sm_probe", "sm_probe.frag");
  StorageBuffer counts("the SM probe's counts");
  counts.reserve(kMaxSmIds);
  kernel.bindStorage(0, counts);
  double ms = 0;
  for (int run = 0; run < 2; ++run) {  // the first compiles and warms up
    counts.zero(kMaxSmIds);
    stream.enable();
    stream.clearDepth(1.0f);
    stream.setWriteSurfaces({0});
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    kernel.execute();
    glFinish();
    ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stream.disable();
  }
  nlohmann::json ids = nlohmann::json::array();
  uint64_t elements = 0;
  const std::vector<float> words = counts.read(kMaxSmIds);
  for (uint32_t id = 0; id < kMaxSmIds; ++id) {
    uint32_t n = 0;
    std::memcpy(&n, &words[id], sizeof n);
    if (n == 0) continue;
    ids.push_back(id);
    elements += n;
  }
  return {{"sms", ids.size()}, {"sm_ids", ids}, {"elements", elements}, {"ms", ms}};
}

}  // namespace

int main(int argc, char** argv) {
  const int width = argc > 1 ? std::atoi(argv[1]) : 2048;
  if (width < 1) {
    std::fprintf(stderr, "measure_sm_probe: WIDTH: '%s' is not a positive integer\n", argv[1]);
    return 1;
  }
  try {
    const auto context = GlContext::create(GlBackend::Auto);
    nlohmann::json out = {{"gl_renderer", context->renderer()}, {"width", width}};
    out["shader_thread_group"] = hasExtension("GL_NV_shader_thread_group");
    if (out["shader_thread_group"]) {
      GLint smCount = 0;
      glGetIntegerv(kSmCountNv, &smCount);
      out["sm_count"] = glGetError() == GL_NO_ERROR && smCount > 0 ? nlohmann::json(smCount) : nlohmann::json(nullptr);
      out["fragment"] = probe(StreamStage::Fragment, width);
      out["compute"] = probe(StreamStage::Compute, width);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "measure_sm_probe: %s\n", e.what());
    return 1;
  }
}
