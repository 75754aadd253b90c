#pragma once
// Cone queries on the stream path (-r 2 --cone): one cone per pixel through
// a structure's cone kernel (kernels_glsl/cone/: kd_cone.frag, bvh_cone.frag),
// the GPU twins of accel/cone/kd_cone_traversal.cpp and bvh_cone_traversal.cpp
// step for step, so both
// renderers give the same count/id/t buffers and node/triangle counts. Needs
// a current GL context.

#include <span>

#include "render/cone_tracer.h"

namespace passtrace {

struct GpuConeConfig {
  int loopLimit = 64;  // -l: node visits per pass (0 = the driver's budget); the state resumes across passes
  // Distinct triangles a cone's list holds with --cone-max 0; a cone meeting
  // more is a one-line error (never a silently short count). With --cone-max
  // N the list holds N.
  uint32_t capacity = 1024;
  // Records (stacks and hits) per band of cones traced together, at most:
  // also capped by the driver's storage-buffer block size. Tests make it
  // small to run several bands.
  uint64_t maxBandBytes = uint64_t(1) << 30;
};

// Throws std::runtime_error (one line) when a list overflows, --cone-max
// exceeds the capacity, or the per-cone records do not fit.
ConeFrame traceConesGpu(const ConeStreamTree& tree, const CameraBasis& camera,
                        float halfAngle, const ConeQueryConfig& config, const GpuConeConfig& gpu);

}  // namespace passtrace
