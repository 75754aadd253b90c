#pragma once
// How many loop iterations one element of a kernel may run in one pass.
//
// llvmpipe ends every loop of a fragment shader invocation, silently, once
// the invocation's loops together have run 65,535 iterations (gallivm's
// LP_MAX_TGSI_LOOP_ITERATIONS). The count is kept per SIMD vector of
// elements, and a vector iterates while any of its lanes does, so in the
// worst case it is the sum of its lanes' iterations. A kernel whose pass
// can run longer (a cone's leaf with thousands of triangles, say) must count
// its iterations and end its pass before this budget, or lose work without a
// sign. Other drivers have no such cap.
#include <cstdint>
#include <string>

namespace passtrace {

// Per element and pass, for the renderer string GL_RENDERER names:
// llvmpipe's cap over its lanes ("llvmpipe (LLVM 15.0.6, 256 bits)": 8 lanes
// of 32 bits), less a margin for the loops a kernel does not count;
// 2^30 elsewhere.
uint32_t shaderLoopBudget(const std::string& glRenderer);
// The same for the current context's GL_RENDERER.
uint32_t currentShaderLoopBudget();

// Loop iterations a traversal kernel may run per step, at most: the step's
// own iteration, the pop loop (amortised: each pushed entry is popped once;
// bvh_stack_traversal.glsl, octree_traversal.glsl) and the small per-axis
// loops a compiler may leave rolled.
inline constexpr uint32_t kLoopIterationsPerStep = 4;

// Traversal steps per element per pass that a kernel runs for -l: 0 asks
// for as many as the budget allows (one pass per bounce, unless a ray needs
// more steps than the cap leaves: it then resumes in the next pass, as at
// any -l); any -l is bounded by the budget, so no pass is cut short.
int passStepLimit(int loopLimit, uint32_t budget);
// The same for the current context.
int passStepLimit(int loopLimit);

}  // namespace passtrace
