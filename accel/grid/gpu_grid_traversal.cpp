#include "accel/grid/gpu_grid_traversal.h"

#include "accel/ray_stream_layout.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"

namespace passtrace {

GpuGridTraversal::GpuGridTraversal(const GridStreamData& grid, const std::vector<glm::vec4>& cells,
                                   const std::vector<glm::vec4>& lists, const std::vector<glm::vec4>& triangleTexels,
                                   uint64_t maxStepsPerRay, AccelStats stats, const GpuTraversalConfig& config)
    : cells_(cells, "grid cells", config.maxPageTexels),
      lists_(lists, "grid triangle lists", config.maxPageTexels),
      triangles_(triangleTexels, "triangles", config.maxPageTexels),
      init_("grid_init", "grid/grid_init.frag"),
      merged_("grid_traverse", "grid/grid_traverse.frag", StreamKernel::Depth::Test,
              {streamPagesDefine({&cells_, &lists_, &triangles_}), triangleTestDefine(config.build.triangleTest)}),
      step_("grid_split_step", "grid/grid_split_step.frag", StreamKernel::Depth::Test, {streamPagesDefine({&cells_})}),
      intersect_("grid_split_intersect", "grid/grid_split_intersect.frag", StreamKernel::Depth::Test,
                 {streamPagesDefine({&lists_, &triangles_}), triangleTestDefine(config.build.triangleTest)}),
      stats_(std::move(stats)),
      maxStepsPerRay_(maxStepsPerRay),
      loopLimit_(config.loopLimit),
      kernels_(config.gridKernels) {
  for (StreamKernel* k : {&init_, &merged_, &step_, &intersect_}) {
    k->set("uGridMin", grid.gridMin);
    k->set("uCellSize", grid.cellSize);
    k->set("uInvCellSize", grid.invCellSize);
    k->set("uGridResolution", grid.resolution);
    k->bindInput("uCells", cells_);
    k->bindInput("uLists", lists_);
    k->bindInput("uTriangles", triangles_);
  }
  merged_.set("uLoopLimit", loopLimit_);
}

uint64_t GpuGridTraversal::trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) {
  for (StreamKernel* k : {&init_, &merged_, &step_, &intersect_}) bindRayInputs(*k, rays);
  rays.setWriteSurfaces({kStateSurface, kAuxSurface});
  init_.execute();
  active -= std::min(active, retire());  // rays that miss the grid
  rays.setWriteSurfaces({kStateSurface, kHitSurface, kAuxSurface});
  if (kernels_ == GridKernels::Split) return traceSplit(active, retire);
  return runTraversalPasses(merged_, active, maxStepsPerRay_ / uint64_t(loopLimit_) + 2, retire);
}

// Purcell's schedule: each kernel serves only the rays waiting for it (the
// others are discarded) and reports how many it served. Keep running the
// kernel that served the most rays last time; switch when its share falls
// below the other's last count, and always after a pass that served none.
uint64_t GpuGridTraversal::traceSplit(uint64_t active, const std::function<uint64_t()>& retire) {
  uint64_t passes = 0, lastStep = active, lastIntersect = 0;
  bool stepping = true;
  const uint64_t maxPasses = 2 * maxStepsPerRay_ + 4;
  while (active > 0) {
    if (passes >= maxPasses)
      throw GlError("grid split kernels: rays still active after " + std::to_string(passes) + " passes");
    StreamKernel& kernel = stepping ? step_ : intersect_;
    const uint64_t served = kernel.execute(true);
    ++passes;
    (stepping ? lastStep : lastIntersect) = served;
    active -= std::min(active, retire());
    if (served == 0 || (stepping ? lastStep < lastIntersect : lastIntersect < lastStep)) stepping = !stepping;
  }
  return passes;
}

}  // namespace passtrace
