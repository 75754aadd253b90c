#pragma once
// --dynamic two-trees and merge on the GPU stream path (kd_dynamic.h): the
// kernels of the row's stream variant, compiled once; each frame only the
// data streams are replaced (GpuKdTraversal::replaceTree).
//   merge:     one traversal of the merged tree.
//   two-trees: the static tree's traversal, then the dynamic tree's, whose
//              init kernel starts from the static hit (KD_CONTINUE). The
//              first traversal's cull retires every ray it finishes, so the
//              stream's depth buffer (which rays are active) is saved
//              before it and restored for the second.

#include <memory>
#include <span>

#include "accel/gpu_traversal.h"
#include "accel/kd/gpu_kd_traversal.h"
#include "accel/kd/kd_dynamic.h"

namespace passtrace {

class GpuKdDynamicTraversal final : public GpuTraversal {
 public:
  // `trees` must outlive it and have been updated for the frame `tris`.
  GpuKdDynamicTraversal(const KdDynamicTrees& trees, KdStreamVariant variant, std::span<const Triangle> tris,
                        const GpuTraversalConfig& config);
  // After trees.update(tris): flattens the frame's tree(s) and replaces the
  // streams. Returns the milliseconds spent flattening (the upload is not
  // counted, as a rebuild's build_ms does not count it).
  double update(std::span<const Triangle> tris);

  // The milliseconds the constructor spent flattening the frame's tree (the
  // merged or the dynamic one), as update() returns them.
  double firstFlattenMs() const { return firstFlattenMs_; }

  uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) override;
  AccelStats stats() const override { return stats_; }

 private:
  const KdDynamicTrees& trees_;
  KdStreamVariant variant_;
  std::unique_ptr<GpuKdTraversal> first_;   // the merged tree, or the static tree
  std::unique_ptr<GpuKdTraversal> second_;  // two-trees: the dynamic tree
  AccelStats stats_;
  AccelStats staticStats_;
  double firstFlattenMs_ = 0;
};

}  // namespace passtrace
