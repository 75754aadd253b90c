#include "tests/gl_test_support.h"

#include <cstdlib>

#include "accel/ray_stream_layout.h"
#include "stream/texel_address.h"

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
  const int width = 64;
  const int height = int((rays.size() + width - 1) / width);
  InOutStream stream(width, std::max(height, 1), kRaySurfaceCount);
  const size_t n = stream.elementCount();
  std::vector<glm::vec4> origin(n, glm::vec4(0.0f)), direction(n, glm::vec4(0, 0, 1, kInfinity)),
      state(n, glm::vec4(packIndex(0), 0, 0, 0)), hit(n, glm::vec4(kInfinity, 0, 0, packIndex(0)));
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool isShadow = i < shadow.size() && shadow[i];
    origin[i] = glm::vec4(rays[i].origin, float(isShadow ? RayKind::Shadow : RayKind::Nearest));
    direction[i] = glm::vec4(rays[i].direction, rays[i].tMax);
    state[i].w = 1.0f;
    hit[i].x = rays[i].tMax;
  }
  stream.upload(kOriginSurface, origin);
  stream.upload(kDirectionSurface, direction);
  stream.upload(kStateSurface, state);
  stream.upload(kHitSurface, hit);

  StreamKernel cull("cull", "cull.frag", StreamKernel::Depth::Cull);
  cull.bindInput("uState", stream, kStateSurface);
  stream.enable();
  stream.clearDepth(1.0f);
  const uint64_t active = n - cull.execute(true);
  TracedRays result;
  result.passes = traversal.trace(stream, active, [&] { return cull.execute(true); });
  stream.disable();
  const std::vector<glm::vec4> hits = stream.read(kHitSurface);
  result.state = stream.read(kStateSurface);
  result.state.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    const glm::vec4& h = hits[i];
    result.hits.push_back(h.x < rays[i].tMax ? Hit{h.x, h.y, h.z, unpackIndex(h.w)} : Hit{rays[i].tMax});
  }
  return result;
}

}  // namespace passtrace::test
