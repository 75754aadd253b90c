#pragma once
// The one interface the GPU stream renderer traces through: an acceleration
// structure's data streams and traversal kernel(s), made by a registry row's
// stream factory (accel/registry.h). Implementations run
// passes over the ray stream (accel/ray_stream_layout.h) until the cull
// kernel has retired every active ray.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "accel/cpu_accelerator.h"
#include "stream/stream_stage.h"

namespace passtrace {

class ConstInputStream;
class InOutStream;
class StreamKernel;

// Issue 17 item 3, fewer passes per bounce: a kernel that runs a primary
// bounce's ray generation, traversal and thesis shading in one pass. It is
// its family's kernels_glsl/<family>/*_fused.frag, which includes camera.glsl
// and shade_thesis.glsl beside its walk; the renderer compiles it with
// `defines`, the STREAM_PAGES of its own streams and `streams` and the
// LARGE_STREAM_PAGES of `largeStream` (texel_address.glsl), sets the
// camera and shading inputs, and calls GpuTraversal::bindFused for the rest.
struct FusedBounce {
  std::string glslFile;
  std::vector<std::string> defines;
  std::vector<const ConstInputStream*> streams;
  const ConstInputStream* largeStream = nullptr;
};

class GpuTraversal {
 public:
  virtual ~GpuTraversal() = default;
  // Traces the `active` rays of the enabled stream: reads the origin,
  // direction, state and hit surfaces, writes state and hit. `retire` runs
  // the cull kernel and returns how many rays it retired. Returns the
  // number of traversal passes.
  virtual uint64_t trace(InOutStream& rays, uint64_t active, const std::function<uint64_t()>& retire) = 0;
  virtual AccelStats stats() const = 0;
  // The structure's fused bounce kernel, or null where it has none.
  virtual const FusedBounce* fusedBounce() const { return nullptr; }
  // Binds the structure's own inputs of its fusedBounce() kernel.
  virtual void bindFused(StreamKernel& /*kernel*/) const {}
};

// How the uniform grid runs on the GPU (--grid-kernels).
enum class GridKernels {
  Merged,  // one traversal+intersection kernel with a loop (the thesis's choice)
  Split    // Purcell's separate traversal and intersection kernels
};

// Live-ray compaction in the GPU renderer (--compact, stream/stream_compaction.h).
enum class Compaction {
  Off,    // the thesis's stream: every generation traced in place
  On,     // generations with at most kCompactLiveFraction of the elements live are compacted
  Always  // every generation, even when every element is live (to measure the cost)
};
// With more live rays than this fraction, gathering costs more than the
// culled blocks save (primary rays: every element is live).
inline constexpr double kCompactLiveFraction = 0.5;
const char* compactionName(Compaction c);

struct GpuTraversalConfig {
  AccelBuildConfig build;
  // Traversal steps per element per pass (tracy's -l; the thesis ran 20).
  // 0 = as many as a pass may run: one pass per bounce. makeStreamStructure
  // hands the structure the resolved value (stream/shader_loop_budget.h).
  int loopLimit = 0;
  GridKernels gridKernels = GridKernels::Merged;
  // Texels per ConstInputStream texture page, 0 = the largest texture the GL
  // accepts (--page-texels; smaller values exercise paging on small scenes).
  uint64_t maxPageTexels = 0;
  // --compact: whether the GPU renderer gathers a generation's live rays into
  // whole 4x4 blocks before tracing them (render/gpu_renderer.h); structures ignore it.
  Compaction compact = Compaction::Off;
  // --stage: which GL stage runs the kernels (stream/stream_stage.h). The
  // session makes it current for the whole run; structures ignore it.
  StreamStage stage = StreamStage::Fragment;
  // Whether the run asked for one pass per bounce (-l 0, or an -l the pass's
  // budget bounds); set by withPassStepLimit. Only then does a structure offer
  // its fused bounce (FusedBounce): at a smaller -l most rays would leave the
  // fused pass unfinished, and the bounce would run again pass by pass.
  bool onePassPerBounce = false;
};

// `config` with its loopLimit resolved for the current context: -l 0 made
// the most a pass may run, any -l bounded by the driver's loop cap
// (stream/shader_loop_budget.h), and onePassPerBounce set where that is what
// -l asked for. Structures are built with the result.
GpuTraversalConfig withPassStepLimit(GpuTraversalConfig config);

// Shared by the implementations: binds the ray surfaces a traversal kernel
// reads (uOrigin, uDirection, uState, uHit, uAux), and runs `kernel` pass
// after pass until `retire` has retired all `active` rays. More than
// `maxPasses` passes means a kernel bug: that throws GlError.
void bindRayInputs(StreamKernel& kernel, const InOutStream& rays);
uint64_t runTraversalPasses(StreamKernel& kernel, uint64_t active, uint64_t maxPasses,
                            const std::function<uint64_t()>& retire);

}  // namespace passtrace
