#pragma once
// A stream kernel's fragment source as a compute shader: the same arithmetic
// over the same elements, one invocation per element instead of one fragment
// of a full-screen quad (StreamKernel::Stage::Compute). Measured because
// drivers may run fragment kernels far slower than compute shaders
// (docs/bench-speed/GPU.md: 25-33x on an NVIDIA H200, about 1x on llvmpipe).

#include <string>

namespace passtrace {

// Invocations per work group along x and along y.
constexpr int kComputeGroupSize = 8;

// Rewrites an assembled fragment kernel:
//   - each `layout(location = N) out vec4 NAME;` becomes a global NAME that is
//     stored, after the kernel's main, to `image2D` unit N (rgba32f);
//   - gl_FragCoord becomes the invocation's pixel centre, (x + 0.5, y + 0.5);
//   - gl_HelperInvocation becomes false (a compute shader has none);
//   - `layout(early_fragment_tests) in;` is dropped: there is no depth test, so
//     every element runs, active or not;
//   - invocations past the uniform `uvec2 uComputeSize_` return at once.
// Throws std::invalid_argument for a kernel that discards: a discarded
// fragment writes nothing, which a store after main cannot express.
std::string computeVariant(std::string fragmentSource);

}  // namespace passtrace
