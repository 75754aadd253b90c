#pragma once
// Dynamic scenes with kd-trees (seed 003 ch. 10, --dynamic): static geometry
// plus moving triangles (Scene::moving), traced frame after frame by one of
// three strategies:
//   rebuild:   one tree over every triangle, built each frame;
//   two-trees: a static tree built once and a dynamic tree over the moving
//              triangles built each frame, both traversed (the dynamic one
//              only up to the static one's hit);
//   merge:     the dynamic tree built each frame and merged into the static
//              tree (kd_merge.h), the merged tree traced.
// Both trees index the scene's triangles by their global ids, so hit ids are
// scene ids whatever the strategy. The static tree is built from the first
// frame: a static triangle is the same in every frame.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel/cpu_accelerator.h"
#include "accel/kd/kd_stream_traversal.h"
#include "accel/kd/kd_tree.h"

namespace passtrace {

enum class DynamicStrategy { Rebuild, TwoTrees, Merge };
std::string_view dynamicStrategyName(DynamicStrategy strategy);  // "rebuild", "two-trees", "merge"
std::optional<DynamicStrategy> dynamicStrategyByName(std::string_view name);

// How a registry row that reads BuildParam::Dynamic traverses: nullopt for
// the CPU stack traversal (kd-tree), else the stream variant (its kernel on
// -r 2, the kernel's CPU mirror on -r 1). Throws std::invalid_argument for a
// row that has no dynamic strategies.
std::optional<KdStreamVariant> kdDynamicVariant(std::string_view structureName);

// A kd-tree over the triangles `ids` of `tris` whose references are the
// global ids (the subset is built, its references mapped back).
KdTree buildKdTreeOver(std::span<const Triangle> tris, std::span<const uint32_t> ids, const AccelBuildConfig& config);

// The trees of a two-trees or merge run, frame after frame.
class KdDynamicTrees {
 public:
  // Builds the static tree over the triangles not flagged in `moving`
  // (empty: nothing moves) of the first frame `tris`.
  KdDynamicTrees(DynamicStrategy strategy, std::span<const Triangle> tris, const std::vector<uint8_t>& moving,
                 const AccelBuildConfig& config);
  DynamicStrategy strategy() const { return strategy_; }
  double staticBuildMs() const { return staticBuildMs_; }
  const AccelBuildConfig& config() const { return config_; }

  // A new frame (the same number of triangles, the static ones unchanged):
  // builds the dynamic tree and, for merge, the merged tree. Returns the
  // milliseconds this took (the merge's restore costs nothing: kd_merge.h).
  double update(std::span<const Triangle> tris);

  const KdTree& staticTree() const { return static_; }
  const KdTree& dynamicTree() const { return dynamic_; }
  const KdTree& mergedTree() const { return merged_; }  // merge only
  size_t triangleCount() const { return triangleCount_; }

 private:
  DynamicStrategy strategy_;
  AccelBuildConfig config_;
  std::vector<uint32_t> movingIds_;
  size_t triangleCount_ = 0;
  double staticBuildMs_ = 0;
  KdTree static_, dynamic_, merged_;
};

// The frame's structure on the CPU: for two-trees the static tree then the
// dynamic one from the static hit (shadow rays: done at the first hit); for
// merge the merged tree. `variant` as kdDynamicVariant; `trees` and `tris`
// must outlive it. stats().buildMs = `frameMs`.
std::unique_ptr<CpuAccelerator> makeKdDynamicCpu(const KdDynamicTrees& trees, std::optional<KdStreamVariant> variant,
                                                 std::span<const Triangle> tris, TriangleTest test,
                                                 std::string name, double frameMs);

}  // namespace passtrace
