// bvh-octant's sequences (accel/bvh/octant_sequences.h): a ray meets the
// nearer triangles first in its own octant's sequence (and the farther first
// in the opposite one), and converting a stack-BVH tree keeps every reference.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

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
    const Hit hit = traverseEscapeSequence(seqs.sequences[octant], ray, false, &own);
    const Hit far = traverseEscapeSequence(seqs.sequences[kOctants - 1 - octant], ray, false, &opposite);
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
  for (const EscapeSequence& seq : seqs.sequences) {
    EXPECT_EQ(seq.texels.size(), seqs.sequences[0].texels.size());
    std::vector<uint32_t> found;
    for (uint32_t i = 0; i < seq.texels.size(); i += seq.texels[i].w >= 0.0f ? 2 : 3)
      if (seq.texels[i].w < 0.0f) found.push_back(unpackIndex(seq.texels[i + 1].w));
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
  }
}

// The stream path's layout (back to back, flattened one octant at a time) is
// the eight sequences concatenated, texel for texel.
TEST(OctantSequences, BackToBackIsTheEightConcatenated) {
  const std::vector<Triangle> tris = testmesh::triangleSoup(300, Aabb{glm::vec3(0.0f), glm::vec3(10.0f)}, 1.5f, 11);
  const Bvh bvh = bvhFromBinaryBvh(buildBvhStackTree(tris, BvhBuilderKind::Sah), tris);
  const OctantSequences apart = flattenOctantSequences(bvh, tris);
  const BackToBackSequences together = flattenOctantSequencesBackToBack(bvh, tris);
  std::vector<glm::vec4> concatenated;
  for (const EscapeSequence& seq : apart.sequences)
    concatenated.insert(concatenated.end(), seq.texels.begin(), seq.texels.end());
  EXPECT_EQ(together.sequenceSize, apart.sequences[0].texels.size());
  EXPECT_EQ(together.floatsPerTriangle, apart.sequences[0].floatsPerTriangle());
  EXPECT_TRUE(together.texels == concatenated);
}

TEST(OctantSequences, EmptyAndLoneLeafTrees) {
  EXPECT_TRUE(octantsOf({}).sequences[0].texels.empty());
  const std::vector<Triangle> one = testmesh::singleTriangle();
  const OctantSequences seqs = octantsOf(one);
  for (const EscapeSequence& seq : seqs.sequences) EXPECT_EQ(seq.triangleCount, 1u);
}

}  // namespace
}  // namespace passtrace
