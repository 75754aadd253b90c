#include "accel/gpu_traversal.h"

#include <algorithm>

#include "accel/ray_stream_layout.h"
#include "stream/gl_error.h"
#include "stream/inout_stream.h"
#include "stream/shader_loop_budget.h"
#include "stream/stream_kernel.h"

namespace passtrace {

GpuTraversalConfig withPassStepLimit(GpuTraversalConfig config) {
  const int most = passStepLimit(0);
  config.onePassPerBounce = config.onePassPerBounce || config.loopLimit <= 0 || config.loopLimit >= most;
  config.loopLimit = passStepLimit(config.loopLimit);
  return config;
}

void bindRayInputs(StreamKernel& kernel, const InOutStream& rays) {
  kernel.bindInput("uOrigin", rays, kOriginSurface);
  kernel.bindInput("uDirection", rays, kDirectionSurface);
  kernel.bindInput("uState", rays, kStateSurface);
  kernel.bindInput("uHit", rays, kHitSurface);
  kernel.bindInput("uAux", rays, kAuxSurface);
}

uint64_t runTraversalPasses(StreamKernel& kernel, uint64_t active, uint64_t maxPasses,
                            const std::function<uint64_t()>& retire) {
  uint64_t passes = 0;
  while (active > 0) {
    if (passes == maxPasses)
      throw GlError(kernel.name() + ": rays still active after " + std::to_string(passes) + " passes");
    kernel.execute();
    ++passes;
    active -= std::min(active, retire());
  }
  return passes;
}

}  // namespace passtrace

namespace passtrace {

const char* compactionName(Compaction c) {
  switch (c) {
    case Compaction::On: return "on";
    case Compaction::Always: return "always";
    case Compaction::Off: break;
  }
  return "off";
}

}  // namespace passtrace
