#pragma once
// The GPU stream renderer (-r 2, thesis figure 8): ray generation, then for
// each bounce traversal passes until the occlusion count says no ray is
// active, then one shading pass that writes the next rays.

#include <chrono>
#include <memory>

#include "accel/gpu_traversal.h"
#include "render/frame_result.h"
#include "render/shading_config.h"
#include "scenes/scene.h"
#include "stream/const_input_stream.h"
#include "stream/inout_stream.h"
#include "render/row_bands.h"
#include "stream/storage_buffer.h"
#include "stream/stream_compaction.h"
#include "stream/stream_kernel.h"

namespace passtrace {

struct CameraBasis;

// Sets raygen.frag's camera uniforms: its rays are primaryRay(basis, ...)'s.
void setRaygenCamera(StreamKernel& raygen, const CameraBasis& basis);
// kernels_glsl/row_bands.glsl's uniform: which rows of the whole image the stream holds.
void setRowBands(StreamKernel& kernel, const RowBands& rows);

class GpuRenderer {
 public:
  // `scene` and `traversal` must outlive the renderer. `maxPageTexels` as in
  // GpuTraversalConfig, for the shading data.
  // `compact`: which generations' live rays are gathered into whole 4x4 blocks
  // before their traversal passes (--compact, stream/stream_compaction.h).
  GpuRenderer(const Scene& scene, GpuTraversal& traversal, int width, int height, uint64_t maxPageTexels = 0,
              ShadingConfig shading = {}, Compaction compact = Compaction::Off);

  // Renders one frame with `bounces` traces (1 = primary rays only). Timing
  // covers ray generation through the last shading pass, ended by glFinish;
  // reading back primary hits (captureHits) is excluded from it.
  // `rows`: the rows of a taller image the streams hold (an MPI rank's, render/row_bands.h).
  FrameResult render(const CameraSpec& camera, int bounces, bool captureHits, const RowBands& rows = {});

  InOutStream& rays() { return rays_; }
  // Whether the last frame's primary bounce ran as the structure's fused pass.
  bool lastFrameFused() const { return lastFrameFused_; }

  // Bytes per pixel this renderer keeps beyond the ray stream the memory
  // check counts for every GL run (render/memory_check.h): the Whitted ray
  // stacks, the compaction's second stream, and in the compute stage each
  // stream's active-element lists (stream/active_elements.h).
  static double extraBytesPerPixel(const ShadingConfig& shading, Compaction compact,
                                   StreamStage stage = StreamStage::Fragment);

  // The scene's triangles moved (--frames with --dynamic, the same count):
  // re-uploads their shading data and the light; the kernels stay compiled.
  void trianglesMoved();

 private:
  uint64_t retireFinished();
  void bindThesisShading();
  void readPrimaryHits(FrameResult& result) const;
  void makeMixKernel();
  // The traversal's fused primary bounce (GpuTraversal::fusedBounce), when it
  // has one and it can serve this frame; false: run the bounce pass by pass.
  bool fusedPrimaryBounce(const CameraBasis& basis, int bounces, bool captureHits, FrameResult& result,
                          std::chrono::steady_clock::duration& excluded);
  void mixLightChanged();

  const Scene& scene_;
  GpuTraversal& traversal_;
  InOutStream rays_;
  uint64_t maxPageTexels_;
  std::unique_ptr<ConstInputStream> triangles_;  // replaced by trianglesMoved()
  ConstInputStream materials_;
  StreamKernel raygen_, cull_, shade_;
  // --shading whitted / ao: their own shading kernels, built only when chosen.
  ShadingConfig shading_;
  std::unique_ptr<ConstInputStream> whittedMaterials_;
  std::unique_ptr<StorageBuffer> whittedStacks_;
  std::unique_ptr<StreamKernel> mixShade_;
  Compaction compact_;
  std::unique_ptr<StreamCompaction> compaction_;  // unless --compact off
  // The fused primary bounce and its count of rays it could not finish; only
  // for structures that offer one, under thesis shading.
  std::unique_ptr<StreamKernel> fused_;
  std::unique_ptr<StorageBuffer> unfinished_;
  bool lastFrameFused_ = false;
};

}  // namespace passtrace
