#pragma once
// The one interface the CPU renderer traces through (an aggregate, in pbrt-v4
// terms), the statistics every structure reports, and the build parameters
// they read. Which structures exist, their names and thesis numbers: the
// registry (accel/registry.h). Brute force is the reference the tests
// compare every structure with; it is no registry row.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "accel/bvh/kay_kajiya_builder.h"
#include "accel/bvh_stack/bvh_builder_kind.h"
#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/kd/kd_build_options.h"
#include "accel/ray_packet.h"
#include "accel/wide_bvh/bvh8_builder_kind.h"
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
  // What one node test and one triangle test read from the structure (the
  // scaling report's bytes per ray against bandwidth); 0 = not stated.
  uint32_t nodeTestBytes = 0;
  uint32_t triangleTestBytes = 0;
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
  // DACRT (accel/dacrt/): no structure is built; these steer its recursion.
  int dacrtRLimit = 20;     // --dacrt-rlimit: trace naively at this many rays or fewer
  int dacrtPLimit = 16;     // --dacrt-plimit: ... or at this many triangles or fewer
  bool dacrtCones = false;  // --dacrt-cones: conic packets of 8x8 primary rays (and shadow rays)
  bool dacrtMedianSplit = false;  // --dacrt-split median: always the spatial median (the seed's baseline)
  BvhBuilderKind bvhBuilder = BvhBuilderKind::Sah;  // --bvh-builder: the stack BVH's builder
  Bvh8BuilderKind bvh8Builder = Bvh8BuilderKind::Binned;  // --bvh8-builder: the tree bvh8 is collapsed from
};

// One generation of rays handed to a batch tracer at once (the CPU renderer
// makes one per bounce: primary rays, then shadow and mirror rays). Element i
// is pixel i of a width x height image when width > 0.
struct RayBatch {
  std::span<const Ray> rays;
  std::span<const uint8_t> active;  // 0: no ray at this element (skip it)
  std::span<const uint8_t> anyHit;  // 1: a shadow ray, any hit before tMax will do
  int width = 0, height = 0;        // the image the elements lie in (8x8 packets); 0 = no layout
  bool primary = false;             // every ray starts at the same point (the camera)
  std::optional<glm::vec3> light;   // shadow rays end at this point (a point light)
  unsigned threads = 0;             // 0: all cores
};

class CpuAccelerator {
public:
  virtual ~CpuAccelerator() = default;
  // Closest hit before ray.tMax, or with anyHit any hit before it. stats, when
  // given, is added to. Safe to call from many threads at once.
  virtual Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const = 0;
  // Batch tracing, for tracers that need all rays of a generation together
  // (DACRT). Only those that say tracesBatches() get called this way; every
  // other structure keeps the renderer's per-ray loop. hits and stats have
  // one entry per element; stats are added to. The default loops over
  // intersect. Returns the tracer's filter counters, if it has any.
  virtual bool tracesBatches() const { return false; }
  virtual std::optional<FilterStats> traceBatch(const RayBatch& batch, std::span<Hit> hits,
                                                std::span<RayStats> stats) const;
  // Packet tracing (bvh8-packet, Embree): the renderer cuts each generation
  // into pixel tiles and hands over a tile's shadow rays, and in the primary
  // generation its closest-hit rays, as packets of up to RayPacket::kMax rays
  // written straight from its camera and paths (no per-frame copies; other
  // rays go one at a time through intersect). packetSize(): the tracer's own
  // packet width (it splits larger packets itself); 0: no packets. Preferred
  // to traceBatch when both are offered. hits and stats have one entry per
  // ray; stats are added to.
  virtual int packetSize() const { return 0; }
  virtual void tracePacket(const RayPacket&, bool /*anyHit*/, std::span<Hit>, std::span<RayStats>) const {}
  // Several packets of the same kind at once, so that a tracer may
  // interleave them: the renderer hands over up to packetsAtOnce() tiles'
  // packets together (1: one tile at a time, as tracePacket). The default
  // traces them one after another.
  virtual int packetsAtOnce() const { return 1; }
  virtual void tracePackets(std::span<const PacketJob> jobs, bool anyHit) const {
    for (const PacketJob& job : jobs) {
      const size_t n = size_t(job.rays->count);
      tracePacket(*job.rays, anyHit, std::span<Hit>(job.hits, n), std::span<RayStats>(job.stats, n));
    }
  }
  virtual std::string name() const = 0;
  virtual AccelStats stats() const = 0;
};

// Tests every triangle in scene order; holds a span of tris as above.
std::unique_ptr<CpuAccelerator> makeBruteForceAccelerator(std::span<const Triangle> tris, TriangleTest test = TriangleTest::MollerTrumbore);

}  // namespace passtrace
