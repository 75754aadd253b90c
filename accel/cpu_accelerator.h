#pragma once
// The one interface the CPU renderer traces through (an aggregate, in pbrt-v4
// terms), the statistics every structure reports, and the build parameters
// they read. Which structures exist, their names and thesis numbers: the
// registry (accel/registry.h). Brute force is the reference the tests
// compare every structure with; it is no registry row.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/kd/kd_build_options.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct AccelStats {
  std::string name;               // the registry row's name, or "brute-force"
  double buildMs = 0;             // construction (and flattening), steady_clock
  double floatsPerTriangle = 0;   // thesis Table 3 accounting, triangles excluded
  size_t nodes = 0;               // tree nodes, internal and leaves
  size_t leaves = 0;
  size_t references = 0;          // triangle references (a kd-tree may repeat some)
  uint32_t depth = 0;             // levels; a single leaf is 1
  // Expected cost of a ray that hits the root's box, by the SAH with the kd
  // builders' constants (kd_sah_cost.h); 0 = not computed for this structure.
  double sahCost = 0;
  uint64_t structureBytes = 0;    // nodes + references as the traversal stores them; 0 = unknown
};

// Construction parameters of every structure (tracy's -c -t -g -e -d).
struct AccelBuildConfig {
  KayKajiyaConfig kayKajiya;  // -c
  int gsTries = 10;           // -t: Goldsmith/Salmon constructions; the cheapest is kept
  uint64_t gsSeed = 0x65;     // shuffles the insertion order of each G/S try
  float gridMultiplier = 1.0f;  // -g: scales the uniform grid's resolution
  int kdMinElements = 2;      // -e: fewest triangles for a kd-tree internal node
  int kdMaxDepth = 0;         // -d: kd-tree maximum depth; 0 = 8 + 1.3 log2 N
  int kdStackSize = 4;        // --stack-size: kd short-stack entries, 1-8
  KdBuilderKind kdBuilder = KdBuilderKind::Exact;        // --kd-builder: exact or binned SAH
  KdTermination kdTermination = KdTermination::Thesis;   // --kd-termination: -e/-d, or the seed's rules
  // --triangle-test: used by every traversal, CPU and GPU (not a build
  // parameter, but every structure is made from this config).
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
};

class CpuAccelerator {
public:
  virtual ~CpuAccelerator() = default;
  // Closest hit before ray.tMax, or with anyHit any hit before it. stats, when
  // given, is added to. Safe to call from many threads at once.
  virtual Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const = 0;
  virtual std::string name() const = 0;
  virtual AccelStats stats() const = 0;
};

// Tests every triangle in scene order; holds a span of tris as above.
std::unique_ptr<CpuAccelerator> makeBruteForceAccelerator(std::span<const Triangle> tris, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
