#pragma once
// The CPU renderer (-r 1): the same rays, bounces and shading as the GPU
// stream renderer, traced through any CpuAccelerator on all cores. Per-ray
// and batch tracers run one wavefront per bounce over all pixels; packet
// tracers take a group of tiles through all its bounces at a time, its path
// states in the cache: passes over a frame of 100-odd-byte path states
// stalled on cache misses.

#include <vector>

#include "accel/cpu_accelerator.h"
#include "render/camera.h"
#include "render/frame_result.h"
#include "render/shading.h"
#include "scenes/scene.h"

namespace passtrace {

class CpuRenderer {
 public:
  // `scene` and `accelerator` must outlive the renderer, and the scene's
  // triangles must not change while it lives (its shading table is built from
  // them here). threads = 0: all cores.
  CpuRenderer(const Scene& scene, const CpuAccelerator& accelerator, unsigned threads = 0,
              ShadingConfig shading = {});

  // `rows`: the rows of a taller image this image is (an MPI rank's, render/row_bands.h).
  FrameResult render(const CameraSpec& camera, int width, int height, int bounces, bool captureHits,
                     const RowBands& rows = {});

 private:
  // What shading an element needs besides its hit and path: one per generation.
  struct Generation {
    const CameraBasis* basis;  // packet rows, primary generation: rays are generated per tile; else null
    int width;
    float epsilon;
    bool last;  // thesis: the last bounce (no further rays)
    int bounces;
    float aoLength;
    std::vector<WhittedStack>* stacks;
    bool keepHits;  // packet rows: store the hits (the primary ones, for --hits); else they stay in the tile
    const RowBands* rows;  // AO's samples follow the whole image's pixel
  };
  void shade(const Generation& g, size_t i, const Hit& hit, PathState& path) const;
  // Starts loading what shading `hit` reads (its shading-table entry and vertex normals).
  void prefetchShading(const Hit& hit) const;

  // The batch path's per-element arrays, kept for all generations of a frame.
  struct BatchScratch {
    std::vector<Ray> rays;
    std::vector<uint8_t> active, anyHit;
    std::vector<RayStats> stats;
  };
  // One bounce through CpuAccelerator::traceBatch; returns the rays traced.
  uint64_t traceGeneration(std::vector<PathState>& paths, std::vector<Hit>& hits, bool primary, int width, int height,
                           FrameStats& frame, BatchScratch& scratch) const;

  // What a frame's tracing did: the rays traced and the generations that traced any.
  struct Traced {
    uint64_t rays;
    int passes;
  };
  // A frame of two or more generations through CpuAccelerator::tracePackets:
  // each group of 8x8 tiles from its camera rays to its last generation,
  // shaded after each, its paths in the thread's scratch; `pixels` gets the
  // colours, steps and counts, `hits` the primary hits if `captureHits`.
  Traced traceTileGroups(const CameraBasis& basis, int width, int height, int generations, int bounces,
                         bool captureHits, const RowBands& rows, std::vector<WhittedStack>& stacks,
                         std::vector<Hit>& hits, FrameResult& pixels) const;
  // A whole frame of primary rays only (thesis shading, -b 1) through
  // CpuAccelerator::tracePacket, without path states: `pixels` gets the
  // colours, steps and counts, `hits` (if given) the hits; returns the rays traced.
  uint64_t tracePrimaryOnly(const CameraBasis& basis, int width, int height, std::vector<Hit>* hits,
                            FrameResult& pixels) const;
  // One bounce ray by ray through CpuAccelerator::intersect; returns the rays traced.
  uint64_t traceRays(std::vector<PathState>& paths, std::vector<Hit>& hits) const;

  const Scene& scene_;
  const CpuAccelerator& accelerator_;
  unsigned threads_;
  ShadingConfig shading_;
  std::vector<ShadingEntry> table_;  // makeShadingTable(scene_)
  // Read from the scene's bounds once here, not per frame (a pass over every triangle).
  float epsilon_;   // secondaryRayEpsilon(scene_)
  float aoLength_;  // aoDistance(scene_, shading_)
};

}  // namespace passtrace
