#pragma once
// A structure's cone query (registry: Structure::cone). One per family:
// kd_cone_traversal.cpp (kd-tree stack traversal, Listing 1),
// bvh_cone_traversal.cpp (BVH stack traversal, nearer child first) and
// brute_force_cone.cpp (every triangle: the tests' reference).

#include <memory>
#include <span>
#include <string>

#include "accel/cone/cone_hit_list.h"
#include "accel/cpu_accelerator.h"

namespace passtrace {

class ConeTraversal {
 public:
  virtual ~ConeTraversal() = default;
  // Thread-safe given one scratch per thread; result.hits is overwritten.
  virtual void query(const Cone& cone, const ConeQueryConfig& config, ConeScratch& scratch,
                     ConeResult& result) const = 0;
  virtual const AccelStats& stats() const = 0;
};

using ConeFactory = std::unique_ptr<ConeTraversal> (*)(std::span<const Triangle>, const AccelBuildConfig&);

// A tree as the stream path's cone kernel reads it (render/gpu_cone_tracer.h):
// the kernel (a kernels_glsl/ file), its ConeTree buffer (layout in the
// kernel's header) and where the parts start, the stack entries a cone can
// need, and the build's stats. The kd-tree's (kd_cone.frag, the tree of
// buildKdTreeFor) and kk-bvh's (bvh_cone.frag) are the CPU rows' trees.
struct ConeStreamTree {
  const char* kernel = "";
  std::vector<float> data;
  uint32_t nodeCount = 0, nodeBase = 0, refBase = 0, triBase = 0;
  uint32_t stackSize = 1;
  AccelStats stats;
};
using ConeStreamFactory = ConeStreamTree (*)(std::span<const Triangle>, const AccelBuildConfig&);
ConeStreamTree makeKdTreeStreamCone(std::span<const Triangle> tris, const AccelBuildConfig& config);
ConeStreamTree makeKkBvhStreamCone(std::span<const Triangle> tris, const AccelBuildConfig& config);

std::unique_ptr<ConeTraversal> makeBruteForceCone(std::span<const Triangle> tris);
// "kd-tree" (SAH, the row's -e/-d/--kd-builder/--kd-termination) and "kd-pbrt".
std::unique_ptr<ConeTraversal> makeKdTreeCone(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<ConeTraversal> makeKdPbrtCone(std::span<const Triangle> tris, const AccelBuildConfig& config);
// Kay/Kajiya BVH ("kk-bvh", -c), walked with a stack rather than its escape sequence.
std::unique_ptr<ConeTraversal> makeKkBvhCone(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
