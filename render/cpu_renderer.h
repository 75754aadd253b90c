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
  CpuRenderer(const Scene& scene, const CpuAccelerator& accelerator, unsigned threads = 0,
              ShadingConfig shading = {});

  FrameResult render(const CameraSpec& camera, int width, int height, int bounces, bool captureHits);

 private:
  // The batch path's per-element arrays, kept for all generations of a frame.
  struct BatchScratch {
    std::vector<Ray> rays;
    std::vector<uint8_t> active, anyHit;
    std::vector<RayStats> stats;
  };
  // One bounce through CpuAccelerator::traceBatch; returns the rays traced.
  uint64_t traceGeneration(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width, int height,
                           FrameStats& frame, BatchScratch& scratch) const;

  // One bounce through CpuAccelerator::tracePacket, 8x4 pixel tiles built
  // from the paths' rays; adds the stats to the paths; returns the rays traced.
  uint64_t tracePackets(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width,
                        int height) const;

  const Scene& scene_;
  const CpuAccelerator& accelerator_;
  unsigned threads_;
  ShadingConfig shading_;
};

}  // namespace passtrace
