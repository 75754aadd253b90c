#pragma once
// The one interface the CPU renderer traces through (an aggregate, in pbrt-v4
// terms), with tracy's accelerator numbering (thesis Table 4, CPU column):
//
//   0 kk-bvh            K/K BVH, sequential (escape-index sequence)
//   1 gs-bvh            G/S BVH, sequential
//   2 kd-tree           Kd-tree (SAH with split clipping, stack traversal)
//   3 kd-pbrt           Kd-tree built the pbrt way
//   4 grid              Uniform grid (3D-DDA)
//   5 kk-bvh-recursive  K/K BVH, recursive
//   6 gs-bvh-recursive  G/S BVH, recursive
//   7 octree            Octree
//
// Brute force has no number in tracy; makeBruteForceAccelerator gives it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "accel/bvh/bvh.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/geometry/geometry.h"
#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/traversal_stats.h"
#include "accel/geometry/triangle_test.h"

namespace passtrace {

struct AccelStats {
  std::string name;               // acceleratorName(), or "brute-force"
  double buildMs = 0;             // construction (and flattening), steady_clock
  double floatsPerTriangle = 0;   // thesis Table 3 accounting, triangles excluded
  size_t nodes = 0;               // tree nodes, internal and leaves
  size_t leaves = 0;
  size_t references = 0;          // triangle references (a kd-tree may repeat some)
  uint32_t depth = 0;             // levels; a single leaf is 1
};

// Construction parameters of every structure (tracy's -c -t -g -e -d).
struct AccelBuildConfig {
  KayKajiyaConfig kayKajiya;  // -c
  int gsTries = 10;           // -t: Goldsmith/Salmon constructions; the cheapest is kept
  uint64_t gsSeed = 0x65;     // shuffles the insertion order of each G/S try
  float gridMultiplier = 1.0f;  // -g: scales the uniform grid's resolution
  int kdMinElements = 2;      // -e: fewest triangles for a kd-tree internal node
  int kdMaxDepth = 0;         // -d: kd-tree maximum depth; 0 = 8 + 1.3 log2 N
  // --triangle-test: used by every traversal, CPU and GPU (not a build
  // parameter, but every structure is made from this config).
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;
};

// The K/K tree flattened to its escape-index sequence, and its statistics
// (buildMs covers construction and flattening). CPU accelerator 0 and the
// GPU stream renderer's accelerator 0 both start from this.
struct SequenceBuild {
  EscapeSequence sequence;
  AccelStats stats;
};
SequenceBuild buildKayKajiyaSequence(std::span<const Triangle> tris, const KayKajiyaConfig& config);

class CpuAccelerator {
public:
  virtual ~CpuAccelerator() = default;
  // Closest hit before ray.tMax, or with anyHit any hit before it. stats, when
  // given, is added to. Safe to call from many threads at once.
  virtual Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const = 0;
  virtual std::string name() const = 0;
  virtual AccelStats stats() const = 0;
};

// Builds accelerator `number` (Table 4) over tris. Lifetime: accelerators hold
// a std::span of tris, so the caller keeps the triangles alive and unchanged
// for the accelerator's lifetime (number 0 in fact copies the vertices into
// its sequence, but callers should not rely on that). Throws
// std::invalid_argument for numbers outside 0-7.
std::unique_ptr<CpuAccelerator> makeCpuAccelerator(int number, std::span<const Triangle> tris,
                                                   const AccelBuildConfig& config = {});

// The two forms every BVH runs in on the CPU: its escape-index sequence,
// walked as the GPU walks it (accelerators 0 and 1), and the recursive descent
// of its tree (5 and 6; holds `tris` as above).
std::unique_ptr<CpuAccelerator> makeSequenceAccelerator(SequenceBuild build, TriangleTest test = TriangleTest::MollerTrumbore);
std::unique_ptr<CpuAccelerator> makeRecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats,
                                                            TriangleTest test = TriangleTest::MollerTrumbore);
// Node, leaf, reference and depth counts of a BVH with one triangle per leaf,
// and its memory as the thesis counts it (8 floats per box), under
// acceleratorName(number). buildMs is left 0.
AccelStats bvhStats(int number, const Bvh& bvh);

// Tests every triangle in scene order; holds a span of tris as above.
std::unique_ptr<CpuAccelerator> makeBruteForceAccelerator(std::span<const Triangle> tris, TriangleTest test = TriangleTest::MollerTrumbore);

// Short names for 0-7 as listed above; throws std::invalid_argument otherwise.
std::string acceleratorName(int number);
// The thesis's long name ("K/K BVH, sequential") for 0-7.
std::string acceleratorThesisName(int number);
// Parses "0".."7" or a short name; throws std::invalid_argument with a
// one-line message listing the valid names for anything else.
int acceleratorNumber(const std::string& nameOrNumber);

}  // namespace passtrace
