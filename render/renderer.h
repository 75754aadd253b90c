#pragma once
// One interface for the four renderers (-r): the OpenGL preview, the CPU ray
// tracer, the GPU stream ray tracer and the CPU ray tracer through Embree.
// A Renderer owns the structure it traces through, built from a registry row.

#include <memory>

#include "accel/registry.h"
#include "render/frame_result.h"
#include "render/row_bands.h"
#include "render/shading_config.h"
#include "scenes/scene.h"

namespace passtrace {

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Renders one view; captureHits also reads back the primary hits.
  virtual FrameResult render(const CameraSpec& camera, bool captureHits) = 0;
  // The structure's statistics; name "none" for the preview.
  virtual AccelStats structureStats() const = 0;
};

struct RendererConfig {
  int width = 512, height = 512;  // the image traced: with `rows` banded, their local rows
  int bounces = 3;         // traces per path, primary and shadow rays included
  unsigned threads = 0;    // CPU renderers; 0 = all cores
  GpuTraversalConfig gpu;  // build parameters (gpu.build) and the stream's own
  ShadingConfig shading;   // --shading, --ao-samples, --ao-distance
  RowBands rows;           // an MPI rank's rows of the whole image (render/row_bands.h); default the whole
};

// Builds `structure` (null for the preview) over `scene` and the renderer
// `id` around it. The GL renderers need a current context. `scene` must
// outlive the renderer.
std::unique_ptr<Renderer> makeRenderer(RendererId id, const Structure* structure, const Scene& scene,
                                       const RendererConfig& config);

}  // namespace passtrace
