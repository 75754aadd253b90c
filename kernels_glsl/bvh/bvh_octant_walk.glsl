// bvh_traverse.frag's escape-index walk over the sequence of the ray's octant
// (accel/bvh/octant_sequences.h): eight sequences of uSequenceSize texels
// back to back, children near-first for their octant, each triangle one
// texel (v0, -packed slot) whose (v1, packed id) and v2 are texels 2 slot and
// 2 slot + 1 of uOctantTriangles, shared by the eight
// (accel/bvh/escape_sequence.h, LeafTexels::Shared), each box one texel of
// grid planes (box_grid.glsl). The walk keeps the index inside the
// ray's own sequence, so it resumes exactly as kk-bvh's.
// Shared by the traversal pass (bvh_octant_traverse.frag) and the fused
// bounce (bvh_octant_fused.frag). Needs texel_address.glsl and intersect.glsl.
#include "bvh/box_grid.glsl"

uniform LargeConstStream uSequences;   // the eight escape-index sequences
uniform ConstStream uOctantTriangles;  // (v1, packed id), v2 of each leaf slot
uniform uint uSequenceSize;            // texels in one sequence: the end of traversal
uniform int uLoopLimit;                // traversal steps per pass (tracy's -l)

// As rayOctant in accel/bvh/octant_sequences.h: a bit per negative component.
uint rayOctant(vec3 direction) {
  return (direction.x < 0.0 ? 1u : 0u) | (direction.y < 0.0 ? 2u : 0u) | (direction.z < 0.0 ? 4u : 0u);
}

// At most uLoopLimit steps from `index`; `index` is uSequenceSize once the
// ray is done. `hit` is (t, u, v, packed id) as intersectTriangle keeps it.
void octantWalk(vec3 origin, vec3 direction, bool anyHit, inout uint index, inout float steps, inout float tests,
                inout vec4 hit) {
  GridRay grid = gridRay(origin, safeInverse(direction));
  uint base = rayOctant(direction) * uSequenceSize;
  int budget = uLoopLimit;
  while (budget > 0 && index < uSequenceSize) {
    // Boxes until a triangle: llvmpipe runs both sides of a divergent branch, so
    // the triangle test stays out of this loop and runs once per triangle below.
    vec4 first = fetchTexel(uSequences, base + index);
    while (budget > 0 && index < uSequenceSize && first.w >= 0.0) {
      steps += 1.0;
      budget -= 1;
      bool enter = intersectsGridBox(grid, first.xyz, hit.x);
      index = enter ? index + 1u : unpackIndex(first.w);
      if (index < uSequenceSize) first = fetchTexel(uSequences, base + index);
    }
    if (budget > 0 && index < uSequenceSize) {
      uint slot = unpackIndex(-first.w);
      vec4 second = fetchTexel(uOctantTriangles, 2u * slot);
      vec4 third = fetchTexel(uOctantTriangles, 2u * slot + 1u);
      steps += 1.0;
      budget -= 1;
      tests += 1.0;
      bool found = intersectTriangle(origin, direction, first.xyz, second.xyz, third.xyz, second.w, hit);
      index = (found && anyHit) ? uSequenceSize : index + 1u;
    }
  }
}
