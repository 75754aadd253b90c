#pragma once
// The kd-tree stream traversals on the GPU (thesis 8.5, seed 003 ch. 6): an
// initialisation kernel, then kernels_glsl/kd/kd_traverse.frag pass after
// pass. The push-down and stack variants keep a per-element record (restart
// root, push-down flag, stack) in a storage buffer (kd_ray_record.glsl).

#include <map>
#include <memory>
#include <vector>

#include "accel/kd/kd_stream_traversal.h"
#include "accel/gpu_traversal.h"
#include "stream/const_input_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {

struct KdTexels;

class GpuKdTraversal final : public GpuTraversal {
 public:
  // continueFromHit (--dynamic two-trees, the second tree): the init kernel
  // starts from the hit a first traversal left in the hit surface, and adds
  // to its step and test counts (kd_init.frag, KD_CONTINUE).
  GpuKdTraversal(KdStreamVariant variant, const KdTexels& texels, const Aabb& sceneBox,
                 const std::vector<glm::vec4>& triangleTexels, uint64_t maxStepsPerRay, uint32_t stackSize,
                 AccelStats stats, const GpuTraversalConfig& config, bool continueFromHit = false);
  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

  // Dynamic scenes: new data between frames without new kernels (llvmpipe
  // compiles a kernel on its first draw, which costs far more than a
  // trace); the traversal kernel is rebuilt only if a stream's page count
  // changes, since STREAM_PAGES is compiled in (and kept for that count).
  // stackSize: the variant's stack entries for the new tree (kd-stack's
  // grows with the tree's depth).
  void replaceTree(const KdTexels& texels, const Aabb& sceneBox, uint64_t maxStepsPerRay, uint32_t stackSize,
                   AccelStats stats);
  void replaceTriangles(const std::vector<glm::vec4>& triangleTexels);

 private:
  void bindStreams(uint32_t compiledPages);
  void setStackSize(uint32_t stackSize);

  KdStreamVariant variant_;
  GpuTraversalConfig config_;
  std::unique_ptr<ConstInputStream> nodes_, lists_, triangles_;
  StreamKernel init_;
  std::map<uint32_t, std::unique_ptr<StreamKernel>> traverseByPages_;  // by STREAM_PAGES
  StreamKernel* traverse_ = nullptr;  // the one for the current streams
  uint32_t compiledPages_ = 0;        // its STREAM_PAGES
  AccelStats stats_;
  uint64_t maxPasses_;
  bool hasRecord_;
  uint32_t stackSize_;
  StorageBuffer records_{"kd-tree ray stacks"};  // grown to the stream's size on the first trace
};

}  // namespace passtrace
