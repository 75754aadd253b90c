// bvh-octant's sequences (accel/bvh/octant_sequences.h): a ray meets the
// nearer triangles first in its own octant's sequence (and the farther first
// in the opposite one), and converting a stack-BVH tree keeps every reference.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "accel/brute_force.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/octant_sequences.h"
#include "accel/bvh_stack/bvh_stack_structure.h"
#include "tests/test_meshes.h"

namespace passtrace {
namespace {

glm::vec3 octantDiagonal(uint32_t octant) {
  return {(octant & 1u) ? -1.0f : 1.0f, (octant & 2u) ? -1.0f : 1.0f, (octant & 4u) ? -1.0f : 1.0f};
}

// 32 small triangles strung along `axis` through the origin, each crossing the line.
std::vector<Triangle> beads(glm::vec3 axis) {
  const glm::vec3 side = glm::normalize(glm::cross(axis, glm::vec3(0.3f, 1.0f, 0.1f)));
  const glm::vec3 up = glm::normalize(glm::cross(axis, side));
  std::vector<Triangle> tris;
  for (int k = 0; k < 32; ++k) {
    const glm::vec3 c = float(k) * 3.0f * axis;
    tris.push_back({c - side - up, c + side - up, c + 2.0f * up});
  }
  return tris;
}

OctantSequences octantsOf(std::span<const Triangle> tris) {
  return flattenOctantSequences(bvhFromBinaryBvh(buildBvhStackTree(tris, BvhBuilderKind::Sah), tris), tris);
}

TEST(OctantSequences, RayMeetsTheNearestTrianglesFirstInItsOwnOctant) {
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    const glm::vec3 d = octantDiagonal(octant);
    const std::vector<Triangle> tris = beads(glm::normalize(d));
    const OctantSequences seqs = octantsOf(tris);
    const Ray ray{-5.0f * d, d};
    ASSERT_EQ(rayOctant(ray.direction), octant);
    RayStats own, opposite;
    const Hit hit = traverseEscapeSequence(seqs.sequence(octant), ray, false, &own);
    const Hit far = traverseEscapeSequence(seqs.sequence(kOctants - 1 - octant), ray, false, &opposite);
    EXPECT_EQ(hit.id, 0u) << "octant " << octant;
    EXPECT_EQ(far.id, 0u) << "octant " << octant;
    // Near first: one leaf (at most bvh-stack's 4 references) before the hit culls every other box.
    EXPECT_LE(own.triangleTests, 4u) << "octant " << octant;
    EXPECT_GE(opposite.triangleTests, 16u) << "octant " << octant << ": the far-first order tests most beads";
  }
}

TEST(OctantSequences, EverySequenceHoldsEveryReferenceOnce) {
  const std::vector<Triangle> tris = testmesh::triangleSoup(500, Aabb{glm::vec3(0.0f), glm::vec3(10.0f)}, 1.5f, 7);
  const BinaryBvh binary = buildBvhStackTree(tris, BvhBuilderKind::Sah);
  const OctantSequences seqs = flattenOctantSequences(bvhFromBinaryBvh(binary, tris), tris);
  std::vector<uint32_t> expected = binary.references;
  std::sort(expected.begin(), expected.end());
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    const SequenceView seq = seqs.sequence(octant);
    std::vector<uint32_t> found;
    for (const glm::vec4& texel : seq.texels)
      if (texel.w < 0.0f) found.push_back(unpackIndex(seq.sharedTriangles[2 * unpackIndex(-texel.w)].w));
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
  }
}

// The stream path's layout, written octant by octant in pieces, is the eight
// shared-leaf sequences concatenated, texel for texel; 45,000 triangles make
// every sequence span several pieces.
TEST(OctantSequences, WrittenPiecesAreTheEightSharedLeafSequences) {
  const std::vector<Triangle> tris = testmesh::triangleSoup(45000, Aabb{glm::vec3(0.0f), glm::vec3(60.0f)}, 1.0f, 11);
  const Bvh bvh = bvhFromBinaryBvh(buildBvhStackTree(tris, BvhBuilderKind::Sah), tris);
  std::vector<glm::vec4> concatenated;
  // The tree as octant 0 orders it, each octant's order from there (ties as octant 0 has them), slots as octant 0 numbers them.
  const BoxGrid grid = octantBoxGrid(bvh);
  const Bvh zeroTree = orderChildrenForOctant(bvh, 0, grid);
  const std::vector<uint32_t> slots = leafSlots(zeroTree);
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    const EscapeSequence seq =
        flattenEscapeSequence(orderChildrenForOctant(zeroTree, octant, grid), tris, LeafTexels::Shared, slots, &grid);
    concatenated.insert(concatenated.end(), seq.texels.begin(), seq.texels.end());
  }
  const OctantZero zero = flattenOctantZero(bvh, tris);
  EXPECT_TRUE(zero.triangles == sharedTriangleTexels(zeroTree, tris));
  ASSERT_EQ(zero.sequence.texels.size() * kOctants, concatenated.size());
  ASSERT_GT(zero.sequence.texels.size(), kOctantWriteTexels);
  std::vector<glm::vec4> written(concatenated.size(), glm::vec4(-7.0f));
  std::vector<bool> seen(written.size(), false);
  size_t pieces = 0;
  writeOctantSequences(zero, tris, [&](uint64_t first, std::span<const glm::vec4> texels) {
    ASSERT_LE(texels.size(), kOctantWriteTexels);
    ASSERT_LE(first + texels.size(), written.size());
    for (size_t i = 0; i < texels.size(); ++i) {
      EXPECT_FALSE(seen[first + i]) << "texel " << first + i << " written twice";
      seen[first + i] = true;
      written[first + i] = texels[i];
    }
    ++pieces;
  });
  EXPECT_GT(pieces, 8u);
  EXPECT_TRUE(written == concatenated);
}

// A shared leaf is one texel (v0, -packed slot); the triangle stream holds
// (v1, packed id) and v2 at 2 slot and 2 slot + 1, slots in depth-first order.
TEST(OctantSequences, SharedLeavesNameTheirTriangle) {
  const std::vector<Triangle> tris = testmesh::triangleSoup(200, Aabb{glm::vec3(0.0f), glm::vec3(10.0f)}, 1.5f, 5);
  const Bvh bvh = bvhFromBinaryBvh(buildBvhStackTree(tris, BvhBuilderKind::Sah), tris);
  const EscapeSequence seq = flattenEscapeSequence(bvh, tris, LeafTexels::Shared);
  const std::vector<glm::vec4> shared = sharedTriangleTexels(bvh, tris);
  ASSERT_EQ(shared.size(), 2 * tris.size());
  std::vector<uint32_t> found;
  uint32_t nextSlot = 0;
  for (uint32_t i = 0; i < seq.texels.size(); i += seq.texels[i].w >= 0.0f ? 2 : 1) {
    if (seq.texels[i].w >= 0.0f) {
      EXPECT_GT(unpackIndex(seq.texels[i].w), i) << "a box's escape lies after it";
      continue;
    }
    const uint32_t slot = unpackIndex(-seq.texels[i].w);
    EXPECT_EQ(slot, nextSlot++) << "slots in depth-first order";
    const uint32_t id = unpackIndex(shared[2 * slot].w);
    ASSERT_LT(id, tris.size());
    EXPECT_EQ(glm::vec3(seq.texels[i]), tris[id].v0);
    EXPECT_EQ(glm::vec3(shared[2 * slot]), tris[id].v1);
    EXPECT_EQ(glm::vec3(shared[2 * slot + 1]), tris[id].v2);
    found.push_back(id);
  }
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found.size(), tris.size());
  EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << "every triangle once";
}

// Rays from afar at every third triangle's centre, and as many beside them
// (a fifth of the way across, some hit elsewhere, some miss).
std::vector<Ray> raysAt(std::span<const Triangle> tris, uint32_t seed) {
  const Aabb bounds = testmesh::boundsOf(tris);
  const float reach = 3.0f * glm::length(bounds.max - bounds.min);
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 1.0f);
  std::vector<Ray> rays;
  for (size_t i = 0; i < tris.size(); i += 3) {
    const glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    const glm::vec3 c = (tris[i].v0 + tris[i].v1 + tris[i].v2) / 3.0f;
    rays.push_back(Ray{c - reach * d, d});
    const glm::vec3 side = glm::normalize(glm::cross(d, glm::vec3(0.3f, 0.5f, 0.8f)));
    rays.push_back(Ray{c - reach * d + 0.2f * reach * side, d});
  }
  return rays;
}

// Quantized boxes are conservative at every scale and far from the origin:
// the walk finds what brute force finds, small, large, offset or flat (the
// grid itself down to 1e-30 and up to 1e30: box_grid_test.cpp; a triangle
// test's products (cubes of lengths) leave float precision beyond about 1e+-10).
TEST(OctantSequences, QuantizedBoxesLoseNoHitAtAnyScale) {
  const struct {
    float scale;
    glm::vec3 offset;
  } placements[] = {{1.0f, glm::vec3(0.0f)},   {1e-9f, glm::vec3(0.0f)}, {1e9f, glm::vec3(0.0f)},
                    {1e-2f, glm::vec3(1e4f)}, {1.0f, glm::vec3(-3e4f, 7.0f, 1e5f)}};
  for (const auto& [scale, offset] : placements) {
    for (const bool flat : {false, true}) {
      std::vector<Triangle> tris = flat ? testmesh::flatGrid(12, 9)
                                        : testmesh::triangleSoup(400, Aabb{glm::vec3(0.0f), glm::vec3(10.0f)}, 1.5f, 3);
      for (Triangle& t : tris)
        for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v = *v * scale + offset;
      const OctantSequences seqs = octantsOf(tris);
      size_t found = 0;
      for (const Ray& ray : raysAt(tris, 9)) {
        const Hit brute = intersectBruteForce(tris, ray, false);
        const Hit walked = traverseEscapeSequence(seqs.sequence(rayOctant(ray.direction)), ray, false);
        ASSERT_EQ(walked.found(), brute.found()) << "scale " << scale << " offset " << offset.x << (flat ? " flat" : "");
        if (walked.found()) {
          EXPECT_EQ(walked.t, brute.t) << "scale " << scale;
        }
        found += brute.found();
      }
      EXPECT_GT(found, tris.size() / 4) << "scale " << scale << (flat ? " flat" : "");
    }
  }
}

TEST(OctantSequences, EmptyAndLoneLeafTrees) {
  EXPECT_TRUE(octantsOf({}).texels.empty());
  const std::vector<Triangle> one = testmesh::singleTriangle();
  const OctantSequences seqs = octantsOf(one);
  ASSERT_EQ(seqs.sequenceTexels, 2u) << "the root's box and its one leaf";
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    EXPECT_EQ(unpackIndex(seqs.sequence(octant).texels[0].w), 2u) << "the root escapes to the end";
    EXPECT_LT(seqs.sequence(octant).texels[1].w, 0.0f);
  }
}

}  // namespace
}  // namespace passtrace
