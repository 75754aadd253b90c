// Cones through the kd-tree (seed 000 Listing 1) as a stream kernel: the
// steps of accel/cone/kd_cone_traversal.cpp, up to uLoopLimit node visits
// per pass (and at most uWorkBudget loop iterations: a leaf may be left
// mid-way and resumed: leafNext is 1 + the next reference, 0 outside a leaf). The cone's state outlives the
// pass in its record (cone_record.glsl). A kd leaf repeats triangles: a
// triangle is tested again but kept only once (the CPU's per-triangle mark).
// Finished elements discard, so the pass's occlusion query counts the rest.
#include "cone/cone_record.glsl"

// The tree: [0..5] root box, nodes at uNodeBase (split, axis, right child,
// first reference, reference count), references at uRefBase, triangles at
// uTriBase.

void main() {
  // Helper lanes' storage writes are discarded (their walk could loop to -l) and reads may lie past
  // the buffer (docs/design.md).
  if (gl_HelperInvocation) return;
  loadRecord(uvec2(gl_FragCoord.xy));
  if (phase >= 2.0) discard;
  if (phase == 0.0) {
    phase = 1.0;
    vec3 lo = vec3(tree[0], tree[1], tree[2]), hi = vec3(tree[3], tree[4], tree[5]);
    if (uNodeCount == 0u || !coneBox(apex, axis, spread, lo, hi, t0, t1)) phase = 2.0;
  }
  int visits = 0;
  while (phase == 1.0) {
    ++work;
    uint at5 = uNodeBase + 5u * node;
    uint axisOf = bitsAt(at5 + 1u);
    if (axisOf != 3u) {
      if (visits == uLoopLimit) break;
      ++visits, ++nodes;
      float split = tree[at5];
      uint right = bitsAt(at5 + 2u);
      float l0 = t0, l1 = t1, r0 = t0, r1 = t1;
      float cut = cutoff();
      bool goLeft = coneSide(apex, axis, spread, axisOf, split, 0u, l0, l1) && l0 <= cut;
      bool goRight = coneSide(apex, axis, spread, axisOf, split, 1u, r0, r1) && r0 <= cut;
      if (goLeft && goRight) {
        bool leftFirst = l0 <= r0;
        uint slot = stackBase + 3u * top;
        rec[slot] = uintBitsToFloat(leftFirst ? right : node + 1u);
        rec[slot + 1u] = leftFirst ? r0 : l0;
        rec[slot + 2u] = leftFirst ? r1 : l1;
        ++top;
        node = leftFirst ? node + 1u : right;
        t0 = leftFirst ? l0 : r0, t1 = leftFirst ? l1 : r1;
        continue;
      }
      if (goLeft || goRight) {
        node = goLeft ? node + 1u : right;
        t0 = goLeft ? l0 : r0, t1 = goLeft ? l1 : r1;
        continue;
      }
    } else {
      if (leafNext == 0u) {  // entering the leaf, not resuming it
        if (visits == uLoopLimit) break;
        ++visits, ++nodes;
        leafNext = 1u;
      }
      uint first = bitsAt(at5 + 3u), refs = bitsAt(at5 + 4u);
      for (; leafNext <= refs && phase == 1.0; ++leafNext) {
        if (!workLeftForTriangle(1u)) break;
        ++work;
        if (!testTriangle(bitsAt(uRefBase + first + leafNext - 1u))) phase = 3.0;
      }
      if (leafNext <= refs || phase != 1.0) break;  // out of work for this pass, or overflowed
      leafNext = 0u;
    }
    bool found = false;  // pop until an entry that can still hold a nearer hit
    while (top > 0u && !found) {
      ++work;
      --top;
      uint slot = stackBase + 3u * top;
      if (rec[slot + 1u] <= cutoff()) {
        node = floatBitsToUint(rec[slot]), t0 = rec[slot + 1u], t1 = rec[slot + 2u];
        found = true;
      }
    }
    if (!found) phase = 2.0;
    if (work + 64u > uWorkBudget) break;
  }
  storeRecord();
}
