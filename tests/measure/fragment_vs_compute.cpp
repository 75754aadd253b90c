// Issue 17 item 5: does the driver run passtrace's fragment kernels far slower
// than the same arithmetic in a compute shader? One pass of kk-bvh's traversal
// kernel (kernels_glsl/bvh/bvh_traverse.frag, unchanged) over the scene's
// primary rays, drawn as the stream layer draws it (a full-screen quad into
// the ray stream's float surfaces) and dispatched as a compute shader made
// from the same assembled source (outputs become image stores, gl_FragCoord
// the invocation's pixel). Both passes start from the same uploaded rays;
// their state and hit surfaces must agree bit for bit, and the tool says so.
// Prints one JSON line: the minimum time of each over the repeats (glFinish
// and a steady clock, after one untimed warm-up) and their ratio.
//
//   build/tests/measure/measure_fragment_vs_compute [SCENE=bunny] [WIDTH=512] [REPEATS=5] [LOOP_LIMIT=0]
//
// LOOP_LIMIT 0 is passtrace's -l 0 (the most one pass may run on this
// driver); rays that need more stay active in both variants alike.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "accel/bvh/bvh_structures.h"
#include "accel/geometry/triangle_test.h"
#include "accel/ray_stream_layout.h"
#include "render/camera.h"
#include "scenes/scene_registry.h"
#include "stream/const_input_stream.h"
#include "stream/gl_context.h"
#include "stream/gl_error.h"
#include "stream/glsl_sources.h"
#include "stream/inout_stream.h"
#include "stream/shader_loop_budget.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"

namespace {

using namespace passtrace;
using Clock = std::chrono::steady_clock;

constexpr int kGroup = 8;  // 8x8 invocations per work group

// The fragment kernel's source as a compute shader. Each `layout(location = N)
// out vec4 NAME` becomes a global written to image unit N at the end;
// gl_FragCoord becomes the invocation's pixel centre. (A kernel that
// discards or tests gl_HelperInvocation would need more; kk-bvh's does neither.)
std::string computeVariant(std::string source) {
  if (std::regex_search(source, std::regex(R"(\bdiscard\s*;|gl_HelperInvocation)")))
    throw GlError("compute variant: the kernel discards or tests helper invocations");
  source = std::regex_replace(source, std::regex(R"(\bgl_FragCoord\b)"), "fragCoord_");
  const std::size_t afterVersion = source.find('\n') + 1;
  source.insert(afterVersion, "vec4 fragCoord_;\n");
  source = std::regex_replace(source, std::regex(R"(layout\(early_fragment_tests\)\s+in;)"), "");
  std::vector<std::pair<int, std::string>> outputs;
  const std::regex output(R"(layout\(location\s*=\s*(\d+)\)\s*out\s+vec4\s+(\w+);)");
  for (std::sregex_iterator it(source.begin(), source.end(), output), end; it != end; ++it)
    outputs.emplace_back(std::stoi((*it)[1]), (*it)[2]);
  source = std::regex_replace(source, output, "vec4 $2;");
  source = std::regex_replace(source, std::regex(R"(void\s+main\s*\(\s*\))"), "void fragmentMain()");
  source += "\nlayout(local_size_x = " + std::to_string(kGroup) + ", local_size_y = " + std::to_string(kGroup) +
            ") in;\nuniform uvec2 uSize_;\n";
  for (const auto& [unit, name] : outputs)
    source += "layout(rgba32f, binding = " + std::to_string(unit) + ") uniform writeonly image2D " + name + "Image_;\n";
  source += "void main() {\n  if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uSize_))) return;\n"
            "  fragCoord_ = vec4(vec2(gl_GlobalInvocationID.xy) + 0.5, 0.5, 1.0);\n  fragmentMain();\n";
  for (const auto& [unit, name] : outputs)
    source += "  imageStore(" + name + "Image_, ivec2(gl_GlobalInvocationID.xy), " + name + ");\n";
  return source + "}\n";
}

GLuint linkCompute(const std::string& source) {
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  std::string log(4096, '\0');
  if (!ok) {
    glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    throw GlError("compute variant: compile failed: " + log.substr(0, log.find('\0')));
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramInfoLog(program, GLsizei(log.size()), nullptr, log.data());
    throw GlError("compute variant: link failed: " + log.substr(0, log.find('\0')));
  }
  return program;
}

struct Rays {
  std::vector<glm::vec4> origin, direction, state, hit;
};

Rays primaryRays(const Scene& scene, int width) {
  const int height = width;
  const CameraBasis basis = makeCameraBasis(scene.camera, width, height);
  Rays r;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = primaryRay(basis, x, y);
      r.origin.push_back(glm::vec4(ray.origin, float(RayKind::Nearest)));
      r.direction.push_back(glm::vec4(ray.direction, kInfinity));
      r.state.push_back(glm::vec4(packIndex(0), 0.0f, 0.0f, 1.0f));
      r.hit.push_back(glm::vec4(kInfinity, 0.0f, 0.0f, packIndex(0)));
    }
  return r;
}

void reset(InOutStream& stream, const Rays& rays) {
  stream.upload(kOriginSurface, rays.origin);
  stream.upload(kDirectionSurface, rays.direction);
  stream.upload(kStateSurface, rays.state);
  stream.upload(kHitSurface, rays.hit);
  glFinish();
}

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string sceneName = argc > 1 ? argv[1] : "bunny";
  const int width = argc > 2 ? std::max(8, std::atoi(argv[2])) : 512;
  const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 5;
  const int loopLimit = argc > 4 ? std::atoi(argv[4]) : 0;
  try {
    const auto context = GlContext::create(GlBackend::Auto);
    const Scene scene = loadScene(sceneName);
    const SequenceBuild built = buildKayKajiyaSequence(scene.triangles, {});
    const ConstInputStream sequence(built.sequence.texels, "the BVH escape-index sequence");
    const std::vector<std::string> defines = {streamPagesDefine({&sequence}),
                                              triangleTestDefine(TriangleTest::MollerTrumbore)};
    const int steps = passStepLimit(loopLimit);
    const auto size = static_cast<uint32_t>(built.sequence.texels.size());

    InOutStream stream(width, width, kRaySurfaceCount);
    const Rays rays = primaryRays(scene, width);

    // The fragment pass, as GpuBvhTraversal draws it.
    StreamKernel fragment("bvh_traverse", "bvh/bvh_traverse.frag", StreamKernel::Depth::Test, defines);
    fragment.bindInput("uSequence", sequence);
    fragment.set("uSequenceSize", size);
    fragment.set("uLoopLimit", steps);
    const char* samplers[] = {"uOrigin", "uDirection", "uState", "uHit"};
    const int surfaces[] = {kOriginSurface, kDirectionSurface, kStateSurface, kHitSurface};
    for (int i = 0; i < 4; ++i) fragment.bindInput(samplers[i], stream, surfaces[i]);
    double fragmentMs = std::numeric_limits<double>::infinity();
    for (int r = -1; r < repeats; ++r) {  // -1: a warm-up (llvmpipe compiles at the first draw)
      reset(stream, rays);
      stream.enable();
      stream.clearDepth(1.0f);
      stream.setWriteSurfaces({kStateSurface, kHitSurface});
      glFinish();
      const auto start = Clock::now();
      fragment.execute();
      glFinish();
      if (r >= 0) fragmentMs = std::min(fragmentMs, millisecondsSince(start));
      stream.disable();
    }
    const std::vector<glm::vec4> fragmentState = stream.read(kStateSurface), fragmentHit = stream.read(kHitSurface);

    // The same source as a compute shader, over the same textures.
    const GLuint program = linkCompute(computeVariant(assembleGlsl("bvh/bvh_traverse.frag", defines).source));
    const auto uniform = [&](const std::string& name) { return glGetUniformLocation(program, name.c_str()); };
    GLint unit = 0;
    for (int i = 0; i < 4; ++i) {
      glBindTextureUnit(GLuint(unit), stream.surfaceTexture(surfaces[i]));
      glProgramUniform1i(program, uniform(samplers[i]), unit++);
    }
    for (uint32_t p = 0; p < sequence.pageCount(); ++p) {
      glBindTextureUnit(GLuint(unit), sequence.texture(p));
      glProgramUniform1i(program, uniform("uSequence.pages[" + std::to_string(p) + "]"), unit++);
    }
    glProgramUniform1ui(program, uniform("uSequence.widthLog2"), sequence.widthLog2());
    glProgramUniform1ui(program, uniform("uSequence.pageLog2"), sequence.pageLog2());
    glProgramUniform1ui(program, uniform("uSequenceSize"), size);
    glProgramUniform1i(program, uniform("uLoopLimit"), steps);
    glProgramUniform2ui(program, uniform("uSize_"), uint32_t(width), uint32_t(width));
    // Outputs at location 0 (state) and 1 (hit), as the fragment pass's draw buffers.
    glBindImageTexture(0, stream.surfaceTexture(kStateSurface), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, stream.surfaceTexture(kHitSurface), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const GLuint groups = GLuint((width + kGroup - 1) / kGroup);
    double computeMs = std::numeric_limits<double>::infinity();
    for (int r = -1; r < repeats; ++r) {
      reset(stream, rays);
      glUseProgram(program);
      const auto start = Clock::now();
      glDispatchCompute(groups, groups, 1);
      glMemoryBarrier(GL_ALL_BARRIER_BITS);
      glFinish();
      if (r >= 0) computeMs = std::min(computeMs, millisecondsSince(start));
    }
    checkGlError("the compute variant");
    const std::vector<glm::vec4> computeState = stream.read(kStateSurface), computeHit = stream.read(kHitSurface);
    uint64_t differ = 0;
    for (std::size_t i = 0; i < computeState.size(); ++i)
      differ += std::memcmp(&computeState[i], &fragmentState[i], sizeof(glm::vec4)) != 0 ||
                std::memcmp(&computeHit[i], &fragmentHit[i], sizeof(glm::vec4)) != 0;
    glDeleteProgram(program);

    const double n = double(width) * width;
    std::printf(
        "{\"scene\": \"%s\", \"width\": %d, \"renderer\": \"%s\", \"loop_limit\": %d, \"fragment_ms\": %.3f, "
        "\"compute_ms\": %.3f, \"fragment_over_compute\": %.3f, \"fragment_mrays_per_s\": %.2f, "
        "\"compute_mrays_per_s\": %.2f, \"elements_that_differ\": %llu}\n",
        sceneName.c_str(), width, reinterpret_cast<const char*>(glGetString(GL_RENDERER)), steps, fragmentMs, computeMs,
        fragmentMs / computeMs, n / fragmentMs / 1e3, n / computeMs / 1e3, static_cast<unsigned long long>(differ));
    return differ == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "measure_fragment_vs_compute: %s\n", e.what());
    return 1;
  }
}
