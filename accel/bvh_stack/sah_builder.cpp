#include "accel/bvh_stack/sah_builder.h"

#include "accel/bvh_stack/bvh_build_driver.h"
#include "accel/bvh_stack/bvh_object_split.h"

namespace passtrace {

BinaryBvh buildBinnedSah(std::span<const Triangle> tris, const BvhStackConfig& config) {
  return buildBinaryBvh(tris, config,
                        [&config](std::vector<BvhBuildRef>& refs, const Aabb& box, uint32_t,
                                  std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right) {
                          const BvhObjectSplit split = findObjectSplit(refs, box, config);
                          if (!split.valid()) {  // every centroid at one point
                            if (refs.size() <= config.maxLeafSize) return false;
                            bvhMedianSplit(refs, left, right);
                            return true;
                          }
                          if (refs.size() <= config.maxLeafSize && leafCost(refs.size(), config) <= split.cost)
                            return false;
                          applyObjectSplit(split, refs, config, left, right);
                          return true;
                        },
                        /*threadSafeSplitter=*/true);
}

}  // namespace passtrace
