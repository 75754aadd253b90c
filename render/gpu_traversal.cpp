#include "render/gpu_traversal.h"

#include <stdexcept>

#include "render/gpu_bvh_traversal.h"

namespace passtrace {

std::unique_ptr<GpuTraversal> makeGpuTraversal(int number, const Scene& scene, const GpuTraversalConfig& config) {
  if (config.loopLimit < 1) throw std::invalid_argument("the loop limit (-l) must be at least 1");
  if (number != 0)
    throw std::invalid_argument("accelerator " + std::to_string(number) + " (" + acceleratorThesisName(number) +
                                ") has no GPU stream version yet");
  SequenceBuild build = buildKayKajiyaSequence(scene.triangles, config.build.kayKajiya);
  return std::make_unique<GpuBvhTraversal>(build.sequence, std::move(build.stats), config.loopLimit);
}

}  // namespace passtrace
