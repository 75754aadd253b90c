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
#include "accel/kd/kd_tree.h"

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

// The stream path's cone query (render/gpu_cone_tracer.h, kernels_glsl/cone/)
// walks a kd-tree texelized from this build: a stream row whose tree is the
// CPU kd-tree's (buildKdTreeFor) registers it.
using ConeStreamTree = KdTree (*)(std::span<const Triangle>, const AccelBuildConfig&);

std::unique_ptr<ConeTraversal> makeBruteForceCone(std::span<const Triangle> tris);
// "kd-tree" (SAH, the row's -e/-d/--kd-builder/--kd-termination) and "kd-pbrt".
std::unique_ptr<ConeTraversal> makeKdTreeCone(std::span<const Triangle> tris, const AccelBuildConfig& config);
std::unique_ptr<ConeTraversal> makeKdPbrtCone(std::span<const Triangle> tris, const AccelBuildConfig& config);
// Kay/Kajiya BVH ("kk-bvh", -c), walked with a stack rather than its escape sequence.
std::unique_ptr<ConeTraversal> makeKkBvhCone(std::span<const Triangle> tris, const AccelBuildConfig& config);

}  // namespace passtrace
