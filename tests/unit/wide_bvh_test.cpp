// The wide BVH (accel/wide_bvh/): both builders give valid binary trees, the
// binned build's SAH cost is within 3 % of the exact sweep's, the collapse
// stores every triangle exactly once with child boxes around their subtrees,
// and the AVX2 and scalar traversals return identical hits and counts (and
// the brute-force nearest hit); packets of rays (bvh8-packet) find what
// single rays and brute force find.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/wide_bvh/binary_bvh.h"
#include "accel/wide_bvh/wide_bvh.h"
#include "accel/wide_bvh/wide_bvh_structure.h"
#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "tests/bvh_checks.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

using test::contains;

using testmesh::NamedMesh;

// Every triangle in exactly one leaf, every node's box around its subtree.
void expectValidBinary(const SahBinaryBvh& bvh, std::span<const Triangle> tris) {
  ASSERT_EQ(bvh.prims.size(), tris.size());
  if (tris.empty()) return;
  std::vector<int> seen(tris.size(), 0), reached(bvh.nodes.size(), 0);
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const uint32_t n = stack.back();
    stack.pop_back();
    ASSERT_LT(n, bvh.nodes.size());
    ASSERT_EQ(reached[n]++, 0);
    const SahBinaryBvhNode& node = bvh.nodes[n];
    if (node.leaf()) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) {
        ++seen[bvh.prims[i]];
        EXPECT_TRUE(contains(node.bounds, tris[bvh.prims[i]].bounds()));
      }
      continue;
    }
    for (uint32_t c : {node.first, node.first + 1}) {
      EXPECT_TRUE(contains(node.bounds, bvh.nodes[c].bounds));
      stack.push_back(c);
    }
  }
  for (size_t i = 0; i < tris.size(); ++i) EXPECT_EQ(seen[i], 1) << "triangle " << i;
}

Aabb laneBox(const WideBvhNode& node, int i) {
  return Aabb{{node.minX[i], node.minY[i], node.minZ[i]}, {node.maxX[i], node.maxY[i], node.maxZ[i]}};
}

// Returns the bounds of everything under `ref` after checking it lies in `box`.
void expectSubtreeInside(const WideBvh& bvh, std::span<const Triangle> tris, uint32_t ref, const Aabb& box,
                         std::vector<int>& seen) {
  if (wideIsLeaf(ref)) {
    for (uint32_t p = wideLeafFirst(ref); p < wideLeafFirst(ref) + wideLeafPacks(ref); ++p) {
      const TrianglePack& pack = bvh.packs[p];
      for (int l = 0; l < kTrianglePackWidth; ++l) {
        if (pack.id[l] == kNoHit) continue;
        ++seen[pack.id[l]];
        EXPECT_TRUE(contains(box, tris[pack.id[l]].bounds()));
        EXPECT_EQ(pack.v0x[l], tris[pack.id[l]].v0.x);
      }
    }
    return;
  }
  const WideBvhNode& node = bvh.nodes[ref];
  for (int i = 0; i < kWideBvhWidth; ++i) {
    if (node.child[i] == kWideEmpty) {
      EXPECT_EQ(node.minX[i], kInfinity);  // the box every ray misses
      continue;
    }
    const Aabb child = laneBox(node, i);
    EXPECT_TRUE(contains(box, child));
    expectSubtreeInside(bvh, tris, node.child[i], child, seen);
  }
}

class WideBvhMeshTest : public ::testing::TestWithParam<NamedMesh> {};

// The same hit to the bit (or, for any-hit rays, `sameHitOnlyFound`: whether one
// was found) and the same counts.
void expectSameHitAndCounts(const Hit& got, const Hit& want, const RayStats& gotStats, const RayStats& wantStats,
                            const std::string& where, bool sameHitOnlyFound = false) {
  ASSERT_EQ(got.found(), want.found()) << where;
  if (!sameHitOnlyFound) {
    EXPECT_EQ(got.t, want.t) << where;
    EXPECT_EQ(got.u, want.u) << where;
    EXPECT_EQ(got.v, want.v) << where;
    EXPECT_EQ(got.id, want.id) << where;
  }
  EXPECT_EQ(gotStats.steps, wantStats.steps) << where;
  EXPECT_EQ(gotStats.triangleTests, wantStats.triangleTests) << where;
}

TEST_P(WideBvhMeshTest, BuildersGiveValidTrees) {
  const auto& tris = GetParam().tris;
  expectValidBinary(buildBinnedSahBvh(tris), tris);
  expectValidBinary(buildExactSahBvh(tris), tris);
}

TEST_P(WideBvhMeshTest, CollapseStoresEveryTriangleOnceInsideItsBoxes) {
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
  std::vector<int> seen(tris.size(), 0);
  if (!tris.empty()) {
    ASSERT_FALSE(bvh.nodes.empty());
    Aabb all;
    for (const Triangle& t : tris) all.extend(t.bounds());
    expectSubtreeInside(bvh, tris, 0, all, seen);
  }
  for (size_t i = 0; i < tris.size(); ++i) EXPECT_EQ(seen[i], 1) << "triangle " << i;
  EXPECT_EQ(bvh.references, tris.size());
}

// Same hits (bit for bit) and counts from both builds of the traversal, and
// brute force's nearest t, for both triangle tests, closest and any hit.
TEST_P(WideBvhMeshTest, Avx2AndScalarTraversalsAgreeWithEachOtherAndBruteForce) {
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 150, 17);
  for (TriangleTest test : {TriangleTest::MollerTrumbore, TriangleTest::Watertight}) {
    for (bool anyHit : {false, true}) {
      for (size_t i = 0; i < rays.size(); ++i) {
        RayStats scalarStats;
        const Hit scalar = traverseWideBvhScalar(bvh, tris, rays[i], anyHit, test, &scalarStats);
        const Hit brute = intersectBruteForce(tris, rays[i], anyHit, nullptr, test);
        ASSERT_EQ(scalar.found(), brute.found()) << "ray " << i;
        // The same arithmetic as brute force: the same nearest t (the id may differ on a tie).
        if (!anyHit && brute.found()) {
          EXPECT_EQ(scalar.t, brute.t) << "ray " << i;
        }
        if (anyHit && scalar.found()) {
          EXPECT_LT(scalar.t, rays[i].tMax) << "ray " << i;
        }
        if (!wideBvhAvx2Available()) continue;
        RayStats avxStats;
        const Hit avx = traverseWideBvhAvx2(bvh, tris, rays[i], anyHit, test, &avxStats);
        EXPECT_EQ(avx.id, scalar.id) << "ray " << i;
        EXPECT_EQ(avx.t, scalar.t) << "ray " << i;
        EXPECT_EQ(avx.u, scalar.u) << "ray " << i;
        EXPECT_EQ(avx.v, scalar.v) << "ray " << i;
        EXPECT_EQ(avxStats.steps, scalarStats.steps) << "ray " << i;
        EXPECT_EQ(avxStats.triangleTests, scalarStats.triangleTests) << "ray " << i;
      }
    }
  }
}

// Packets of 64 (incoherent rays: the hardest case for shared traversal)
// find what each ray finds alone: the same nearest t, closest or any hit;
// also when the last few live rays leave the packet (singleRayAt 2), and when
// every ray does at the root (kWidePacketMax: then the counts are the
// single-ray traversal's too, so the hand-over is seen to happen, and the
// packet's own ray set-up, preparePacket, is seen to equal prepare()'s).
// There the mix gets axis-parallel rays through vertices as well: their
// origins lie exactly on leaf boxes' planes, where the slab test reads the
// parallel flags (with a packet's own order they would hit several triangles
// at one vertex, ties in t broken either way).
TEST_P(WideBvhMeshTest, PacketTraversalFindsWhatSingleRaysFind) {
  if (!wideBvhAvx2Available()) GTEST_SKIP() << "no AVX2";
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
  const Aabb bounds = testmesh::boundsOf(tris);
  const std::vector<Ray> mix = testmesh::rayMix(bounds, 150, 17);
  std::vector<Ray> withVertexRays = mix;
  for (size_t i = 0; i < std::min<size_t>(tris.size(), 40); ++i)
    for (int axis = 0; axis < 3; ++axis)
      for (float sign : {1.0f, -1.0f}) {
        Ray ray{tris[i].v1, glm::vec3(0.0f), kInfinity};
        ray.origin[axis] = sign > 0.0f ? bounds.min[axis] - 1.0f : bounds.max[axis] + 1.0f;
        ray.direction[axis] = sign;
        withVertexRays.push_back(ray);
      }
  // acrossRaysAt 1: every leaf tested across the rays of each group that reaches it.
  for (const PacketConfig config : {PacketConfig{0, 0}, PacketConfig{2, 0}, PacketConfig{kWidePacketMax, 0},
                                    PacketConfig{0, 1}, PacketConfig{2, 1}, PacketConfig{0, 5}, PacketConfig{2, 1, 1},
                                    kClosestHitPackets, kAnyHitPackets}) {
    const int singleRayAt = config.singleRayAt;
    const std::vector<Ray>& rays = singleRayAt == kWidePacketMax ? withVertexRays : mix;
    for (bool anyHit : {false, true}) {
      for (size_t begin = 0; begin < rays.size(); begin += kWidePacketMax) {
        const size_t count = std::min<size_t>(kWidePacketMax, rays.size() - begin);
        std::vector<Hit> hits(count);
        std::vector<RayStats> stats(count);
        traceWideBvhPacketAvx2(bvh, RayPacket::of(std::span<const Ray>(rays.data() + begin, count)), anyHit, hits,
                               stats, config);
        for (size_t k = 0; k < count; ++k) {
          const Ray& ray = rays[begin + k];
          RayStats alone;
          const Hit single = traverseWideBvhAvx2(bvh, tris, ray, anyHit, TriangleTest::MollerTrumbore, &alone);
          const std::string where = "ray " + std::to_string(begin + k) + " singleRayAt " + std::to_string(singleRayAt) +
                                    " acrossRaysAt " + std::to_string(config.acrossRaysAt) + " nodesAcrossAt " +
                                    std::to_string(config.nodesAcrossAt);
          ASSERT_EQ(hits[k].found(), single.found()) << where;
          if (!anyHit) {
            EXPECT_EQ(hits[k].t, single.t) << where;
          } else if (hits[k].found()) {
            EXPECT_LT(hits[k].t, ray.tMax) << where;
          }
          if (!tris.empty()) {
            EXPECT_GT(stats[k].steps, 0u) << where;
          }
          if (singleRayAt == kWidePacketMax) {
            EXPECT_EQ(stats[k].steps, alone.steps) << where;
            EXPECT_EQ(stats[k].triangleTests, alone.triangleTests) << where;
          }
        }
      }
    }
  }
}

// Leaves and inner nodes tested across rays (PacketConfig::acrossRaysAt,
// nodesAcrossAt, which only any-hit packets read) against the same packets
// tested ray by ray: each ray does
// the same arithmetic on the same triangles and boxes, so a closest hit is the
// same triangle, t, u and v to the bit, an any-hit ray finds a hit exactly
// when it did, and every count is equal. On coherent packets (an 8x8 tile of
// rays from one eye, where whole groups reach a node, most of them in one
// octant; one tile's every other ray with a zero x direction, an
// axis-parallel slab, which is left to the ray-by-ray test) and on the
// incoherent mix, in groups from every live ray (1) up.
TEST_P(WideBvhMeshTest, AcrossRaysFindAndCountWhatRaysAloneDo) {
  if (!wideBvhAvx2Available()) GTEST_SKIP() << "no AVX2";
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
  const Aabb bounds = testmesh::boundsOf(tris);
  const glm::vec3 centre = 0.5f * (bounds.min + bounds.max), size = bounds.max - bounds.min;
  const glm::vec3 eye = centre + glm::vec3(0.2f, 0.3f, 2.0f) * glm::max(size.x, glm::max(size.y, size.z));
  std::vector<Ray> rays = testmesh::rayMix(bounds, 100, 5);
  for (int tile = 0; tile < 16; ++tile)
    for (int i = 0; i < kWidePacketMax; ++i) {
      const glm::vec3 target = bounds.min + size * glm::vec3((tile % 4 + (i % 8) / 8.0f) / 4.0f,
                                                             (tile / 4 + (i / 8) / 8.0f) / 4.0f, 0.5f);
      rays.push_back(Ray{eye, glm::normalize(target - eye), kInfinity});
    }
  const glm::vec3 front(centre.x, centre.y, eye.z);
  for (int i = 0; i < kWidePacketMax; ++i) {
    const glm::vec3 target = bounds.min + size * glm::vec3(i % 2 == 0 ? 0.5f : 0.5f + i / 256.0f, i / 64.0f, 0.5f);
    glm::vec3 direction = target - front;
    if (i % 2 == 0) direction.x = 0.0f;
    rays.push_back(Ray{front, glm::normalize(direction), kInfinity});
  }
  const PacketConfig configs[] = {{0, 1, 0}, {0, 4, 0}, {0, 8, 0}, {0, 0, 1}, {0, 0, 4}, {0, 0, 8}, {0, 4, 4}};
  for (const PacketConfig& config : configs)
    for (bool anyHit : {false, true})
      for (size_t begin = 0; begin < rays.size(); begin += kWidePacketMax) {
        const size_t count = std::min<size_t>(kWidePacketMax, rays.size() - begin);
        const RayPacket packet = RayPacket::of(std::span<const Ray>(rays.data() + begin, count));
        std::vector<Hit> alone(count), across(count);
        std::vector<RayStats> aloneStats(count), acrossStats(count);
        traceWideBvhPacketAvx2(bvh, packet, anyHit, alone, aloneStats, PacketConfig{0, 0});
        traceWideBvhPacketAvx2(bvh, packet, anyHit, across, acrossStats, config);
        for (size_t k = 0; k < count; ++k) {
          const std::string where = "ray " + std::to_string(begin + k) + " acrossRaysAt " +
                                    std::to_string(config.acrossRaysAt) + " nodesAcrossAt " +
                                    std::to_string(config.nodesAcrossAt);
          expectSameHitAndCounts(across[k], alone[k], acrossStats[k], aloneStats[k], where, anyHit);
        }
      }
}

// bvh8-packet's batch entry point on an image-shaped batch (a partly inactive
// 13x7 image: tiles cut at the edges) of camera rays, then of shadow rays to a
// point mixed with reflection-like rays: brute force's nearest t and any-hit answer.
// Packets traced together (traceWideBvhPacketsAvx2; taking turns a visit at a
// time, more of them than walk at once, so slots are reused; and not) against
// the same packets traced one at a time: every hit and count the same, to the bit.
// Packets of many sizes, some over 32 rays (then all walk with 64-bit masks).
TEST_P(WideBvhMeshTest, PacketsTracedTogetherEqualOneAtATime) {
  if (!wideBvhAvx2Available()) GTEST_SKIP() << "no AVX2";
  const auto& tris = GetParam().tris;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
  const std::vector<Ray> rays = testmesh::rayMix(testmesh::boundsOf(tris), 300, 29);
  std::vector<RayPacket> packets;
  const size_t sizes[] = {32, 7, 64, 1, 20, 32, 45, 3};
  for (size_t begin = 0, k = 0; begin < rays.size(); ++k) {
    const size_t count = std::min(sizes[k % std::size(sizes)], rays.size() - begin);
    packets.push_back(RayPacket::of(std::span<const Ray>(rays.data() + begin, count)));
    begin += count;
  }
  for (const PacketConfig config : {PacketConfig{0, 0}, PacketConfig{3, 1, 1}, PacketConfig{kWidePacketMax, 0},
                                    kClosestHitPackets, kAnyHitPackets}) {
    for (bool anyHit : {false, true}) {
      for (size_t first : {size_t(0), size_t(2)}) {  // from packet 2 on: only packets of up to 32 rays at the end
        const size_t n = first == 0 ? packets.size() : 5;
        std::vector<Hit> together(n * kWidePacketMax), alone(n * kWidePacketMax);
        std::vector<RayStats> togetherStats(together.size()), aloneStats(alone.size());
        std::vector<PacketJob> jobs;
        for (size_t k = 0; k < n; ++k) {
          const RayPacket& packet = packets[first + k];
          const size_t at = k * kWidePacketMax, m = size_t(packet.count);
          jobs.push_back(PacketJob{&packet, together.data() + at, togetherStats.data() + at});
          traceWideBvhPacketAvx2(bvh, packet, anyHit, std::span<Hit>(alone.data() + at, m),
                                 std::span<RayStats>(aloneStats.data() + at, m), config);
        }
        for (bool takeTurns : {true, false}) {
          std::fill(togetherStats.begin(), togetherStats.end(), RayStats{});
          traceWideBvhPacketsAvx2(bvh, jobs, anyHit, config, takeTurns);
          for (size_t k = 0; k < n; ++k)
            for (int r = 0; r < packets[first + k].count; ++r) {
              const size_t i = k * kWidePacketMax + size_t(r);
              const std::string where = "packet " + std::to_string(first + k) + " ray " + std::to_string(r) +
                                        " singleRayAt " + std::to_string(config.singleRayAt) + " anyHit " +
                                        std::to_string(anyHit) + " takeTurns " + std::to_string(takeTurns);
              expectSameHitAndCounts(together[i], alone[i], togetherStats[i], aloneStats[i], where);
            }
        }
      }
    }
  }
}

TEST_P(WideBvhMeshTest, PacketBatchesEqualBruteForce) {
  const auto& tris = GetParam().tris;
  const std::unique_ptr<CpuAccelerator> accel = makeBvh8PacketCpu(tris, AccelBuildConfig{});
  const Aabb box = testmesh::boundsOf(tris);
  const glm::vec3 centre = tris.empty() ? glm::vec3(0.0f) : 0.5f * (box.min + box.max);
  const glm::vec3 eye = centre + glm::vec3(0.3f, 0.4f, 3.0f), light = centre + glm::vec3(-0.5f, 2.0f, 1.0f);
  constexpr int kW = 13, kH = 7;
  std::vector<Ray> rays(kW * kH);
  std::vector<uint8_t> active(rays.size()), anyHit(rays.size());
  for (bool primary : {true, false}) {
    for (int i = 0; i < kW * kH; ++i) {
      const glm::vec3 target = centre + glm::vec3(float(i % kW) / kW - 0.5f, float(i / kW) / kH - 0.5f, 0.0f);
      active[i] = i % 11 != 3;
      anyHit[i] = !primary && i % 3 != 0;
      if (primary || !anyHit[i]) {
        rays[i] = Ray{eye, glm::normalize(target - eye), kInfinity};
      } else {
        rays[i] = Ray{target, glm::normalize(light - target), glm::length(light - target)};
      }
    }
    RayBatch batch{rays, active, anyHit, kW, kH, primary, light, 2};
    std::vector<Hit> hits(rays.size());
    std::vector<RayStats> stats(rays.size());
    accel->traceBatch(batch, hits, stats);
    for (size_t i = 0; i < rays.size(); ++i) {
      if (!active[i]) continue;
      const Hit brute = intersectBruteForce(tris, rays[i], anyHit[i] != 0, nullptr, TriangleTest::MollerTrumbore);
      ASSERT_EQ(hits[i].found(), brute.found()) << "element " << i << " primary " << primary;
      if (!anyHit[i] && brute.found()) {
        EXPECT_EQ(hits[i].t, brute.t) << "element " << i;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, WideBvhMeshTest, ::testing::ValuesIn(testmesh::standardMeshes()),
                         [](const auto& info) { return info.param.name; });

TEST(WideBvh, EmptyMeshHasNoNodesAndNoHits) {
  const std::vector<Triangle> none;
  const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(none), none);
  EXPECT_TRUE(bvh.nodes.empty());
  EXPECT_FALSE(traverseWideBvhScalar(bvh, none, Ray{}, false, TriangleTest::MollerTrumbore, nullptr).found());
}

// A mid-size mesh (a 40k-triangle random soup plus a 20k-triangle sphere):
// the binned build's SAH cost is at most 3 % above the exact sweep's, and not
// below it by more than the sweep's own greediness allows.
TEST(WideBvh, BinnedSahCostWithinThreePercentOfExactSweep) {
  std::vector<Triangle> tris = testmesh::triangleSoup(40000, Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)}, 0.05f, 5);
  const std::vector<Triangle> sphere = testmesh::uvSphere(100, 100, glm::vec3(0.5f), 0.4f);
  tris.insert(tris.end(), sphere.begin(), sphere.end());
  const double binned = bvhSahCost(buildBinnedSahBvh(tris));
  const double exact = bvhSahCost(buildExactSahBvh(tris));
  ASSERT_GT(exact, 0.0);
  EXPECT_LE(binned, exact * 1.03) << "binned " << binned << " exact " << exact;
  EXPECT_GE(binned, exact * 0.97) << "binned " << binned << " exact " << exact;
  // Deterministic: the same tree cost on every build, whatever the task order.
  EXPECT_EQ(bvhSahCost(buildBinnedSahBvh(tris)), binned);
}

// Scenes of any size: soups of triangles from 1e-30 to 1e30 in size, at the
// origin and far from it (where the float grid is coarse against the
// triangles). At 1e30 every surface area overflows float, so SAH cannot rank
// the splits (the binned build halves at the median instead of indexing
// past its bins). Every child box holds its subtree, and rays through the
// triangles' vertices along the axes (exactly on the boxes' planes) and a mix
// of others find brute force's hit, closest and any, in both builds.
TEST(WideBvh, TrianglesFromTinyToHugeLoseNoHit) {
  for (const float size : {1e-30f, 1e-6f, 1.0f, 1e6f, 1e30f})
    for (const float away : {0.0f, 1e3f}) {
      const glm::vec3 offset(away * size, -0.5f * away * size, 3.0f * size);
      std::vector<Triangle> tris = testmesh::triangleSoup(400, Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)}, 0.3f, 5);
      for (Triangle& t : tris)
        for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v = *v * size + offset;
      const std::string where = "size " + std::to_string(size) + " away " + std::to_string(away);
      const WideBvh bvh = collapseToWideBvh(buildBinnedSahBvh(tris), tris);
      const Aabb bounds = testmesh::boundsOf(tris);
      std::vector<int> seen(tris.size(), 0);
      expectSubtreeInside(bvh, tris, 0, bounds, seen);
      for (size_t i = 0; i < tris.size(); ++i) EXPECT_EQ(seen[i], 1) << where << " triangle " << i;
      std::vector<Ray> rays = testmesh::rayMix(bounds, 40, 3);
      for (size_t i = 0; i < tris.size(); i += 7)
        for (int axis = 0; axis < 3; ++axis) {
          Ray ray{tris[i].v2, glm::vec3(0.0f), kInfinity};
          ray.origin[axis] = bounds.min[axis] - (bounds.max[axis] - bounds.min[axis]);
          ray.direction[axis] = 1.0f;
          rays.push_back(ray);
        }
      for (const bool anyHit : {false, true})
        for (size_t i = 0; i < rays.size(); ++i) {
          const Hit brute = intersectBruteForce(tris, rays[i], anyHit, nullptr, TriangleTest::MollerTrumbore);
          std::vector<Hit> got{traverseWideBvhScalar(bvh, tris, rays[i], anyHit, TriangleTest::MollerTrumbore, nullptr)};
          if (wideBvhAvx2Available())
            got.push_back(traverseWideBvhAvx2(bvh, tris, rays[i], anyHit, TriangleTest::MollerTrumbore, nullptr));
          for (const Hit& hit : got) {
            ASSERT_EQ(hit.found(), brute.found()) << where << " ray " << i << " any hit " << anyHit;
            if (!anyHit && brute.found()) {
              EXPECT_EQ(hit.t, brute.t) << where << " ray " << i;
            }
          }
        }
    }
}

}  // namespace
}  // namespace passtrace
