#pragma once
// A stream kernel's fragment source as a compute shader: the same arithmetic
// over the same elements, one invocation per element instead of one fragment
// of a full-screen quad (the compute stage, stream/stream_stage.h). Drivers
// may run fragment kernels far slower than compute shaders: on the NVIDIA
// H100 and H200 only 4 of the chip's SMs run pixel shaders
// (docs/bench-speed/GPU.md), on llvmpipe both are the same SIMD loops.
//
// What the fragment stage's depth test and occlusion query do, the variant
// does with index lists (stream/active_elements.h): an invocation either
// takes an element of the stream's rows in 8x8 tiles (every element active)
// or the next index of the active list, dispatched indirectly.

#include <string>

namespace passtrace {

// Invocations per work group: one 8x8 tile of the stream, or 64 consecutive
// entries of the active list.
constexpr int kComputeGroupSize = 64;
constexpr int kComputeTileSide = 8;
// Storage-buffer bindings the variant takes for itself (the kernels use 0-2).
constexpr int kActiveListBinding = 7;   // the elements this dispatch runs
constexpr int kNextListBinding = 6;     // the cull kernel's output: the elements still active
constexpr int kPassedCountBinding = 5;  // elements that did not discard (the occlusion count)
constexpr int kStreamSurfacesBinding = 4;  // the enabled stream's surfaces (InOutStream::surfaceBuffer)

// Rewrites an assembled fragment kernel:
//   - each `layout(location = N) out vec4 NAME;` becomes a global NAME that is
//     stored, after the kernel's main, when bit N of `uWriteMask_` is set (a
//     surface the pass writes): to the element's slot (stream/element_slots.h)
//     past `uOutputSlotN_` in the storage block at kStreamSurfacesBinding, or
//     with `uStoreImages_` to `imageBuffer` unit N (rgba32f);
//   - `uniform sampler2D` (a stream surface) becomes `samplerBuffer`, and
//     COMPUTE_STAGE is defined, which switches texel_address.glsl's
//     readElement and readElementAt to the tile-order slots;
//   - `discard;` (allowed in main only) ends the element's work with nothing
//     stored; gl_FragDepth becomes a local that is never read;
//   - gl_FragCoord becomes the element's pixel centre, gl_HelperInvocation
//     false (a compute shader has none), `layout(early_fragment_tests)` goes;
//   - with `uCull_`, the elements that discard (those still active) are
//     appended to the next active list, and the others are retired;
//   - with `uCountPassed_`, the elements that did not discard are counted.
// Throws std::invalid_argument for a discard outside main, which the
// variant's return cannot express. The variant needs GL_ARB_shader_ballot and
// GL_ARB_gpu_shader_int64 (llvmpipe and NVIDIA's driver have both); without
// them its compile fails with the driver's message, one line.
std::string computeVariant(std::string fragmentSource);

}  // namespace passtrace
