#pragma once
// The CPU renderer (-r 1): the same rays, bounces and shading as the GPU
// stream renderer, one wavefront per bounce over all pixels, traced through
// any CpuAccelerator on all cores.

#include <vector>

#include "accel/cpu_accelerator.h"
#include "render/frame_result.h"
#include "render/shading.h"
#include "scenes/scene.h"

namespace passtrace {

class CpuRenderer {
 public:
  // `scene` and `accelerator` must outlive the renderer. threads = 0: all cores.
  CpuRenderer(const Scene& scene, const CpuAccelerator& accelerator, unsigned threads = 0);

  FrameResult render(const CameraSpec& camera, int width, int height, int bounces, bool captureHits);

 private:
  // One bounce through CpuAccelerator::traceBatch; returns the rays traced.
  uint64_t traceGeneration(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width, int height,
                           FrameStats& frame) const;

  const Scene& scene_;
  const CpuAccelerator& accelerator_;
  unsigned threads_;
};

}  // namespace passtrace
