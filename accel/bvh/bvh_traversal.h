#pragma once
// CPU traversals of a BVH in its two forms: the escape-index sequence, walked
// exactly as the GLSL kernel walks it (thesis Algorithm 4), and the recursive
// descent of section 9.2 over the tree it was flattened from. Both visit the
// same nodes in the same order with the same tests, so on one tree they find
// the same hit and count the same steps; the sequential form only drops the
// call stack (the "partial evaluation" of section 9.4.2).
//
// Why a copy and not one source: the kernel resumes across passes (its state
// packed into RGBA32F surfaces, at most -l steps per pass, the stack-free
// formulation the thesis needs), the mirror runs each ray to completion; a
// GLSL-compatible C++ subset shared by both would need macros for texel
// fetches, `precise` and the pass structure, and hide the very loop a reader
// compares with the thesis. The copy is held to the kernel instead:
// tests/gpu_traversal_test.cpp checks, for every registry row with a stream
// kernel, the same hits and the same step and triangle-test counts per ray.
//
// Both start from best = Hit{t = ray.tMax}: hits at or beyond tMax are
// ignored. With anyHit, traversal stops at the first triangle hit. `test`
// picks the ray/triangle test (accel/geometry/triangle_test.h). Origin and
// direction are used as given (no normalisation).

#include <span>

#include "accel/bvh/bvh.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

// Where a ray stands in the sequence between passes, as the GPU keeps it in
// the state and hit surfaces.
struct EscapeCursor {
  uint32_t index = 0;  // next texel to read; the sequence size when done
  Hit best;            // set best.t = ray.tMax before the first step
  RayStats stats;
};

// Runs at most maxSteps iterations of algorithm 4 from `cursor`, exactly as
// one pass of kernels_glsl/bvh/bvh_traverse.frag with loop limit maxSteps.
// Returns true while the ray still has work.
bool stepEscapeSequence(const SequenceView& seq, const Ray& ray, bool anyHit, EscapeCursor& cursor,
                        uint32_t maxSteps, TriangleTest test = TriangleTest::MollerTrumbore);

// stats, when given, is added to (not reset): one step per box or triangle read.
Hit traverseEscapeSequence(const SequenceView& seq, const Ray& ray, bool anyHit, RayStats* stats = nullptr,
                           TriangleTest test = TriangleTest::MollerTrumbore);

// Real recursion, one call per visited node, children in stored order; the
// depth is the tree's depth, so keep to trees of sane depth (K/K trees of
// real scenes are a few dozen levels).
Hit traverseBvhRecursive(const Bvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                         RayStats* stats = nullptr, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
