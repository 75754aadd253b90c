#include "accel/bvh_stack/middle_builder.h"

#include "accel/bvh_stack/bvh_build_driver.h"

namespace passtrace {

BinaryBvh buildMiddleCut(std::span<const Triangle> tris, const BvhStackConfig& config) {
  return buildBinaryBvh(tris, config,
                        [](std::vector<BvhBuildRef>& refs, const Aabb&, uint32_t, std::vector<BvhBuildRef>& left,
                           std::vector<BvhBuildRef>& right) {
                          const Aabb centroids = bvhCentroidBox(refs);
                          const glm::vec3 e = centroids.extent();
                          const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
                          const float middle = centroids.center()[axis];
                          for (const BvhBuildRef& r : refs) (r.box.center()[axis] < middle ? left : right).push_back(r);
                          return true;  // an empty side: the driver's median split
                        },
                        /*threadSafeSplitter=*/true);
}

}  // namespace passtrace
