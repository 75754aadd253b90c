#pragma once
// The renderer of a --frames sequence under --dynamic two-trees or merge
// (accel/kd/kd_dynamic.h): the static kd-tree is built once, and each frame
// only the dynamic tree is built (and merged). The CPU renderer gets a new
// accelerator over the frame's trees; the GPU stream renderer keeps its
// kernels and replaces its data streams. (--dynamic rebuild is the ordinary
// per-frame makeRenderer.)

#include <memory>

#include "accel/kd/kd_dynamic.h"
#include "render/renderer.h"

namespace passtrace {

class DynamicRenderer : public Renderer {
 public:
  // The one-time static build, in milliseconds.
  virtual double staticBuildMs() const = 0;
  // The scene (held by reference, reloaded in place) moved to a new frame:
  // builds the dynamic tree, merges, and updates the renderer. Returns the
  // frame's build (or build and merge) milliseconds, flattening included.
  virtual double nextFrame() = 0;
};

// `structure` must be a kd row that reads BuildParam::Dynamic, `id` the CPU
// or the GPU stream renderer, `strategy` two-trees or merge. Builds the static
// tree over `scene` (its first frame); call nextFrame() before rendering.
std::unique_ptr<DynamicRenderer> makeDynamicRenderer(DynamicStrategy strategy, RendererId id, const Structure& structure,
                                                     const Scene& scene, const RendererConfig& config);

}  // namespace passtrace
