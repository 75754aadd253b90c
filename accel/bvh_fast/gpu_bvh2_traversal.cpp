#include "accel/bvh_fast/gpu_bvh2_traversal.h"

#include <algorithm>
#include <string>
#include <vector>

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

// An empty scene still binds one (childless) node: a stream needs texels.
std::vector<glm::vec4> orPadding(const std::vector<glm::vec4>& texels, size_t count) {
  return texels.empty() ? std::vector<glm::vec4>(count, glm::vec4(0.0f)) : texels;
}

}  // namespace

GpuBvh2Traversal::GpuBvh2Traversal(const Bvh2Texels& texels, AccelStats stats, const GpuTraversalConfig& config)
    : nodes_(orPadding(texels.nodes, 4), "bvh-fast nodes", config.maxPageTexels),
      triangles_(orPadding(texels.triangles, 3), "triangles", config.maxPageTexels),
      init_("bvh2_init", "bvh_fast/bvh2_init.frag", StreamKernel::Depth::Test, {}),
      traverse_("bvh2_traverse", "bvh_fast/bvh2_traverse.frag", StreamKernel::Depth::Test,
                {streamPagesDefine({&nodes_, &triangles_}), triangleTestDefine(config.build.triangleTest),
                 "BVH2_STACK_DEPTH " + std::to_string(std::max(1u, texels.depth))}),
      stats_(std::move(stats)),
      // Each step visits a node, none twice; bounded as if -l were 1, since
      // passes over a few long rays ran past nodes / -l + 2 in the tests.
      maxPasses_(texels.nodes.size() / 4 + 2),
      stackDepth_(std::max(1u, texels.depth)) {
  init_.set("uEmpty", texels.nodes.empty() ? 1 : 0);
  traverse_.bindInput("uNodes", nodes_);
  traverse_.bindInput("uTriangles", triangles_);
  traverse_.set("uLoopLimit", config.loopLimit);
  traverse_.set("uStackDepth", stackDepth_);
  traverse_.bindStorage(0, stacks_);
}

uint64_t GpuBvh2Traversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(traverse_, rays);
  stacks_.reserve(uint64_t(rays.elementCount()) * 2 * stackDepth_);
  traverse_.set("uStreamWidth", uint32_t(rays.width()));
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // everything, in an empty scene
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
