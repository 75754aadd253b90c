#include "tests/gl_test_support.h"

#include <cstdlib>

#include "render/stream_ray_query.h"

namespace passtrace::test {

GlContext& glContext() {
  static std::unique_ptr<GlContext> context = [] {
    const char* backend = std::getenv("PASSTRACE_GL_BACKEND");
    return GlContext::create(parseGlBackend(backend ? backend : "auto"));
  }();
  // PASSTRACE_STREAM_STAGE=compute runs the GL tests' streams and kernels in
  // the compute stage (stream/stream_stage.h), as -r 2 --stage compute does.
  static const StreamStageScope stage([] {
    const char* name = std::getenv("PASSTRACE_STREAM_STAGE");
    const std::optional<StreamStage> parsed = parseStreamStage(name ? name : "fragment");
    if (!parsed) throw std::runtime_error(std::string("PASSTRACE_STREAM_STAGE: not fragment or compute: ") + name);
    return *parsed;
  }());
  return *context;
}

TracedRays traceOnGpu(GpuTraversal& traversal, const std::vector<Ray>& rays, const std::vector<bool>& shadow) {
  std::vector<uint8_t> anyHit(rays.size(), 0);
  for (size_t i = 0; i < rays.size() && i < shadow.size(); ++i) anyHit[i] = shadow[i] ? 1 : 0;
  TracedRays result;
  result.hits.resize(rays.size());
  result.state.resize(rays.size());
  StreamRayQuery query(traversal);
  result.passes = query.trace(rays, anyHit, result.hits, {}, result.state);
  for (size_t i = 0; i < rays.size(); ++i)
    if (!result.hits[i].found()) result.hits[i] = Hit{rays[i].tMax};
  return result;
}
}  // namespace passtrace::test
