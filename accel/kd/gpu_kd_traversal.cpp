#include "accel/kd/gpu_kd_traversal.h"

#include <algorithm>

#include "accel/kd/kd_texels.h"
#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

std::vector<std::string> defines(KdStreamVariant variant, std::string pages, TriangleTest test) {
  std::vector<std::string> out = {pages, triangleTestDefine(test)};
  if (variant == KdStreamVariant::Backtrack) out.push_back("KD_BACKTRACK");
  if (kdRestartsFromPushDownRoot(variant)) out.push_back("KD_PUSHDOWN");
  if (kdHasStack(variant)) out.push_back("KD_STACK");
  if (kdHasRayRecord(variant)) out.push_back("KD_RECORD");
  if (variant == KdStreamVariant::Compact) out.push_back("KD_COMPACT");
  return out;
}

std::vector<std::string> initDefines(KdStreamVariant variant, bool continueFromHit) {
  std::vector<std::string> out;
  if (kdHasRayRecord(variant)) out.push_back("KD_RECORD");
  if (continueFromHit) out.push_back("KD_CONTINUE");
  return out;
}

std::string kernelName(KdStreamVariant variant) {
  switch (variant) {
    case KdStreamVariant::Restart: return "kd_restart";
    case KdStreamVariant::Backtrack: return "kd_backtrack";
    case KdStreamVariant::PushDown: return "kd_pushdown";
    case KdStreamVariant::ShortStack: return "kd_shortstack";
    case KdStreamVariant::PushDownShortStack: return "kd_pushdown_shortstack";
    case KdStreamVariant::Stack: return "kd_stack";
    case KdStreamVariant::Compact: return "kd_compact";
  }
  return "kd";
}

}  // namespace

GpuKdTraversal::GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                               const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay,
                               uint32_t stackSize, AccelStats stats, const GpuTraversalConfig& config,
                               bool continueFromHit)
    : variant_(variant),
      config_(config),
      nodes_(std::make_unique<ConstInputStream>(texels.nodes, "kd-tree nodes", config.maxPageTexels)),
      lists_(std::make_unique<ConstInputStream>(texels.lists, "kd-tree triangle lists", config.maxPageTexels)),
      triangles_(std::make_unique<ConstInputStream>(triangleTexels, "triangles", config.maxPageTexels)),
      init_("kd_init", "kd/kd_init.frag", StreamKernel::Depth::Test, initDefines(variant, continueFromHit)),
      stats_(std::move(stats)),
      maxPasses_(maxStepsPerRay / uint64_t(config.loopLimit) + 2),
      hasRecord_(kdHasRayRecord(variant)),
      stackSize_(stackSize) {
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  if (hasRecord_) init_.bindStorage(0, records_);
  bindStreams(0);
  setStackSize(stackSize);
}

void GpuKdTraversal::bindStreams(uint32_t compiledPages) {
  const uint32_t pages = std::max({1u, nodes_->pageCount(), lists_->pageCount(), triangles_->pageCount()});
  if (pages != compiledPages) {
    std::unique_ptr<StreamKernel>& kernel = traverseByPages_[pages];
    if (!kernel) {
      kernel = std::make_unique<StreamKernel>(
          kernelName(variant_), "kd/kd_traverse.frag", StreamKernel::Depth::Test,
          defines(variant_, streamPagesDefine({nodes_.get(), lists_.get(), triangles_.get()}),
                  config_.build.triangleTest));
      kernel->set("uLoopLimit", config_.loopLimit);
      if (hasRecord_) {
        kernel->set("uStackSize", stackSize_);
        kernel->bindStorage(0, records_);
      }
    }
    traverse_ = kernel.get();
    compiledPages_ = pages;
  }
  traverse_->bindInput("uNodes", *nodes_);
  traverse_->bindInput("uLists", *lists_);
  traverse_->bindInput("uTriangles", *triangles_);
}

void GpuKdTraversal::setStackSize(uint32_t stackSize) {
  stackSize_ = stackSize;
  if (!hasRecord_) return;
  init_.set("uStackSize", stackSize_);
  for (auto& [pages, kernel] : traverseByPages_) kernel->set("uStackSize", stackSize_);
}

void GpuKdTraversal::replaceTree(const KdTexels& texels, const Aabb& sceneBox, uint64_t maxStepsPerRay,
                                 uint32_t stackSize, AccelStats stats) {
  nodes_ = std::make_unique<ConstInputStream>(texels.nodes, "kd-tree nodes", config_.maxPageTexels);
  lists_ = std::make_unique<ConstInputStream>(texels.lists, "kd-tree triangle lists", config_.maxPageTexels);
  init_.set("uSceneMin", sceneBox.min);
  init_.set("uSceneMax", sceneBox.max);
  stats_ = std::move(stats);
  maxPasses_ = maxStepsPerRay / uint64_t(config_.loopLimit) + 2;
  bindStreams(compiledPages_);
  setStackSize(stackSize);
}

void GpuKdTraversal::replaceTriangles(const std::vector<glm::vec4>& triangleTexels) {
  triangles_ = std::make_unique<ConstInputStream>(triangleTexels, "triangles", config_.maxPageTexels);
  bindStreams(compiledPages_);
}

uint64_t GpuKdTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  bindRayInputs(init_, rays);
  bindRayInputs(*traverse_, rays);
  if (hasRecord_) {
    // One record per element: 4 header floats and 3 per stack entry (kd_ray_record.glsl).
    records_.reserve(uint64_t(rays.elementCount()) * (4 + 3 * uint64_t(stackSize_)));
    for (StreamKernel* k : {&init_, traverse_}) k->set("uStreamWidth", uint32_t(rays.width()));
  }
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the scene box
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  return runTraversalPasses(*traverse_, active, maxPasses_, retire);
}

}  // namespace passtrace
