// Cones through kk-bvh's tree as a stream kernel: the steps of
// accel/cone/bvh_cone_traversal.cpp's stack traversal (nearer child first),
// up to uLoopLimit stack entries per pass (and at most uWorkBudget loop
// iterations); the record (cone_record.glsl) keeps the stack (node, t0, -)
// and the hits across passes. A BVH leaf holds one triangle, met once.
// The node-sorted variant (--cone-nodes sorted) is CPU only.
#include "cone/cone_record.glsl"

// The tree: nodes at uNodeBase (box min, box max, triangle, first child,
// child count: 9 floats), the child lists at uRefBase, triangles at uTriBase.

const uint MAX_CHILDREN = 64u;

void main() {
  // Helper lanes' storage writes are discarded (their walk could loop to -l) and reads may lie past
  // the buffer (docs/design.md).
  if (gl_HelperInvocation) return;
  loadRecord(uvec2(gl_FragCoord.xy));
  if (phase >= 2.0) discard;
  if (phase == 0.0) {
    phase = 1.0;
    float r0 = 0.0, r1 = CONE_INF;
    if (uNodeCount > 0u) {
      uint n = uNodeBase;
      vec3 lo = vec3(tree[n], tree[n + 1u], tree[n + 2u]), hi = vec3(tree[n + 3u], tree[n + 4u], tree[n + 5u]);
      if (coneBox(apex, axis, spread, lo, hi, r0, r1)) {
        rec[stackBase] = uintBitsToFloat(0u);
        rec[stackBase + 1u] = r0;
        top = 1u;
      }
    }
  }
  for (int i = 0; i < uLoopLimit && phase == 1.0 && top > 0u; ++i) {
    if (!workLeftForTriangle(2u)) break;
    uint entry = floatBitsToUint(rec[stackBase + 3u * (top - 1u)]);
    float entryT0 = rec[stackBase + 3u * (top - 1u) + 1u];
    uint n = uNodeBase + 9u * entry;
    uint children = bitsAt(n + 8u);
    // A node's children and their insertion sort must fit in this pass too.
    if (work > 0u && work + children * (children + 1u) + 2u > uWorkBudget) break;
    ++work;
    --top;
    if (entryT0 > cutoff()) continue;
    ++nodes;
    if (children == 0u) {
      if (!testTriangle(bitsAt(n + 6u))) phase = 3.0;
      continue;
    }
    // The children the cone reaches, pushed farthest first (a stable
    // insertion sort by t0, as std::sort sorts a few entries).
    uint first = bitsAt(n + 7u), pushed = 0u;
    for (uint j = 0u; j < children && pushed < MAX_CHILDREN; ++j) {
      ++work;
      uint child = bitsAt(uRefBase + first + j);
      uint m = uNodeBase + 9u * child;
      vec3 lo = vec3(tree[m], tree[m + 1u], tree[m + 2u]), hi = vec3(tree[m + 3u], tree[m + 4u], tree[m + 5u]);
      float c0 = 0.0, c1 = CONE_INF;
      if (!coneBox(apex, axis, spread, lo, hi, c0, c1) || !(c0 <= cutoff())) continue;
      uint slot = top + pushed;
      while (slot > top && rec[stackBase + 3u * (slot - 1u) + 1u] < c0) {  // farther first
        ++work;
        rec[stackBase + 3u * slot] = rec[stackBase + 3u * (slot - 1u)];
        rec[stackBase + 3u * slot + 1u] = rec[stackBase + 3u * (slot - 1u) + 1u];
        --slot;
      }
      rec[stackBase + 3u * slot] = uintBitsToFloat(child);
      rec[stackBase + 3u * slot + 1u] = c0;
      ++pushed;
    }
    top += pushed;
  }
  if (phase == 1.0 && top == 0u) phase = 2.0;
  storeRecord();
}
