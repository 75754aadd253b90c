#pragma once
// Shared set-up for tests that need OpenGL: one context per test process
// (PASSTRACE_GL_BACKEND picks the backend, default auto; PASSTRACE_STREAM_STAGE
// the stage of its streams and kernels, default fragment), and a ray stream
// that traces hand-made rays through a GpuTraversal.

#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "accel/geometry/geometry.h"
#include "accel/gpu_traversal.h"
#include "stream/gl_context.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"

namespace passtrace::test {

// Creates the process's context on first use; fails the test if none can be made.
GlContext& glContext();

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override { glContext(); }
};

// Rays laid out as elements of a width x height ray stream (the last ones
// padded with finished elements), traced by `traversal` until done.
struct TracedRays {
  std::vector<Hit> hits;
  std::vector<glm::vec4> state;  // final traversal state per ray
  uint64_t passes = 0;
};
TracedRays traceOnGpu(GpuTraversal& traversal, const std::vector<Ray>& rays, const std::vector<bool>& shadow = {});

}  // namespace passtrace::test
