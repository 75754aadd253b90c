// Issue 17 item 5: does the driver run passtrace's fragment kernels far slower
// than the same arithmetic in a compute shader? One pass of kk-bvh's traversal
// kernel (kernels_glsl/bvh/bvh_traverse.frag, unchanged) over the scene's
// primary rays, drawn as the stream layer draws it (a full-screen quad into
// the ray stream's float surfaces) and dispatched as a compute shader made
// from the same source (StreamKernel::Stage::Compute, stream/compute_variant.h:
// outputs become image stores, gl_FragCoord the invocation's pixel). Both passes start from the same uploaded rays;
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
#include <string>
#include <vector>

#include "accel/bvh/bvh_structures.h"
#include "accel/geometry/triangle_test.h"
#include "accel/milliseconds_since.h"
#include "accel/ray_stream_layout.h"
#include "render/camera.h"
#include "scenes/scene_registry.h"
#include "stream/const_input_stream.h"
#include "stream/gl_context.h"
#include "stream/inout_stream.h"
#include "stream/shader_loop_budget.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"

namespace {

using namespace passtrace;
using Clock = std::chrono::steady_clock;

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

    InOutStream stream(width, width, kRaySurfaceCount, StreamStage::Fragment);
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

    // The same source as a compute shader (StreamKernel::Stage::Compute), over
    // the same rays in a compute-stage stream (its surfaces are buffers).
    InOutStream computeStream(width, width, kRaySurfaceCount, StreamStage::Compute);
    StreamKernel compute("bvh_traverse", "bvh/bvh_traverse.frag", StreamKernel::Stage::Compute, defines);
    compute.bindInput("uSequence", sequence);
    compute.set("uSequenceSize", size);
    compute.set("uLoopLimit", steps);
    for (int i = 0; i < 4; ++i) compute.bindInput(samplers[i], computeStream, surfaces[i]);
    compute.bindOutput(0, computeStream, kStateSurface);  // as the fragment pass's draw buffers
    compute.bindOutput(1, computeStream, kHitSurface);
    double computeMs = std::numeric_limits<double>::infinity();
    for (int r = -1; r < repeats; ++r) {
      reset(computeStream, rays);
      const auto start = Clock::now();
      compute.dispatch(width, width);
      glFinish();
      if (r >= 0) computeMs = std::min(computeMs, millisecondsSince(start));
    }
    const std::vector<glm::vec4> computeState = computeStream.read(kStateSurface),
                                 computeHit = computeStream.read(kHitSurface);
    uint64_t differ = 0;
    for (std::size_t i = 0; i < computeState.size(); ++i)
      differ += std::memcmp(&computeState[i], &fragmentState[i], sizeof(glm::vec4)) != 0 ||
                std::memcmp(&computeHit[i], &fragmentHit[i], sizeof(glm::vec4)) != 0;

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
