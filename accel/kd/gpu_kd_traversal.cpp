#include "accel/kd/gpu_kd_traversal.h"

#include <algorithm>

#include "accel/kd/kd_texels.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

std::vector<std::string> defines(KdStreamVariant variant, std::string pages, TriangleTest test) {
  if (variant == KdStreamVariant::Backtrack) return {"KD_BACKTRACK", pages, triangleTestDefine(test)};
  return {pages, triangleTestDefine(test)};
}

std::vector<std::string> initDefines(bool continueFromHit) {
  if (continueFromHit) return {"KD_CONTINUE"};
  return {};
}

}  // namespace

GpuKdTraversal::GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                               const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay, AccelStats stats,
                               const GpuTraversalConfig& config, bool continueFromHit)
    : variant_(variant),
      config_(config),
      nodes_(std::make_unique<ConstInputStream>(texels.nodes, "kd-tree nodes", config.maxPageTexels)),
      lists_(std::make_unique<ConstInputStream>(texels.lists, "kd-tree triangle lists", config.maxPageTexels)),
      triangles_(std::make_unique<ConstInputStream>(triangleTexels, "triangles", config.maxPageTexels)),
      init_("kd_init", "kd/kd_init.frag", StreamKernel::Depth::Test, initDefines(continueFromHit)),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2) {
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  bindStreams(0);
}

void GpuKdTraversal::bindStreams(uint32_t compiledPages) {
  const uint32_t pages = std::max({1u, nodes_->pageCount(), lists_->pageCount(), triangles_->pageCount()});
  if (pages != compiledPages) {
    std::unique_ptr<StreamKernel>& kernel = traverseByPages_[pages];
    if (!kernel) {
      kernel = std::make_unique<StreamKernel>(
          variant_ == KdStreamVariant::Backtrack ? "kd_backtrack" : "kd_restart", "kd/kd_traverse.frag",
          StreamKernel::Depth::Test,
          defines(variant_, streamPagesDefine({nodes_.get(), lists_.get(), triangles_.get()}),
                  config_.build.triangleTest));
      kernel->set("uLoopLimit", config_.loopLimit);
    }
    traverse_ = kernel.get();
    compiledPages_ = pages;
  }
  traverse_->bindInput("uNodes", *nodes_);
  traverse_->bindInput("uLists", *lists_);
  traverse_->bindInput("uTriangles", *triangles_);
}

void GpuKdTraversal::replaceTree(const KdTexels& texels, const Aabb& sceneBox, uint64_t maxStepsPerRay,
                                 AccelStats stats) {
  nodes_ = std::make_unique<ConstInputStream>(texels.nodes, "kd-tree nodes", config_.maxPageTexels);
  lists_ = std::make_unique<ConstInputStream>(texels.lists, "kd-tree triangle lists", config_.maxPageTexels);
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  stats_ = std::move(stats);
  maxPasses_ = maxStepsPerRay / uint64_t(config_.loopLimit) + 2;
  bindStreams(compiledPages_);
}

void GpuKdTraversal::replaceTriangles(const std::vector<glm::vec4>& triangleTexels) {
  triangles_ = std::make_unique<ConstInputStream>(triangleTexels, "triangles", config_.maxPageTexels);
  bindStreams(compiledPages_);
}

uint64_t GpuKdTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(*traverse_, rays);
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(*traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
