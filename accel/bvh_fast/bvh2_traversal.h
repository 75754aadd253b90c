#pragma once
// The bvh-fast kernel's algorithm on the CPU over the same texels
// (kernels_glsl/bvh_fast/bvh2_traverse.frag does the same steps): the GPU
// tests compare its steps and triangle tests with the kernel's, ray for ray.
// One step visits one node: both children are tested (a box, or a single
// triangle in place of its box), the nearer entered child is taken and the
// other pushed with its entry distance; with none, pop the nearest entry not
// beyond the best hit. No box test of the root: the root's children are.

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "accel/bvh_fast/bvh2_texels.h"
#include "accel/cpu_accelerator.h"

namespace passtrace {

struct Bvh2Cursor {
  uint32_t node = 0;
  std::vector<std::pair<uint32_t, float>> stack;  // (node, entry distance), the nearest last
  Hit best;
  RayStats stats;
  bool done = false;
};

// One step of the traversal; sets cursor.done when the ray is finished.
void stepBvh2(const Bvh2Texels& texels, const Ray& ray, const glm::vec3& invDir, bool anyHit, Bvh2Cursor& cursor,
              TriangleTest test);

// The whole traversal (a CpuAccelerator over the texels).
std::unique_ptr<CpuAccelerator> makeBvh2Mirror(Bvh2Texels texels, AccelStats stats, TriangleTest test);

}  // namespace passtrace
