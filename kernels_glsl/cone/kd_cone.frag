// Cones through the kd-tree (seed 000 Listing 1) as a stream kernel: the
// steps of accel/cone/kd_cone_traversal.cpp, up to uLoopLimit node visits
// per pass. All of a cone's state outlives the pass in its record of
// ConeRecords (render/gpu_cone_tracer.cpp sizes it), at float
// e * (8 + 3 uStackSize + 2 uCapacity) for element e:
//   [0] phase: 0 not started, 1 running, 2 done, 3 its list overflowed
//   [1] node (uint bits), [2] t0, [3] t1, [4] stack top, [5] hit count,
//   [6] nodes visited, [7] triangle references met (uint bits)
//   then uStackSize entries (node, t0, t1) and uCapacity hits (t, id):
//   the distinct triangles met, sorted by (t, id). A kd leaf repeats
//   triangles: a triangle is tested again but inserted only when its
//   (t, id) is not already in the list (the CPU's per-triangle mark).
// Finished elements discard, so the pass's occlusion query counts the rest.
#include "cone/cone_record.glsl"

// The tree: [0..5] root box, nodes at uNodeBase (split, axis, right child,
// first reference, reference count), references at uRefBase, triangles at
// uTriBase.

void main() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  uint e = at.y * uStreamWidth + at.x;
  uint base = e * (8u + 3u * uStackSize + 2u * uCapacity);
  float phase = rec[base];
  if (phase >= 2.0) discard;
  uint stackBase = base + 8u;
  hitBase = stackBase + 3u * uStackSize;
  uint c = 4u + 16u * e;
  vec3 apex = vec3(cones[c], cones[c + 1u], cones[c + 2u]);
  vec3 axis = vec3(cones[c + 3u], cones[c + 4u], cones[c + 5u]);
  vec3 k = vec3(cones[c + 6u], cones[c + 7u], cones[c + 8u]);
  dvec3 s = dvec3(apex);
  dvec3 v = dvec3(doubleAt(c + 10u), doubleAt(c + 12u), doubleAt(c + 14u));
  double cosA = doubleAt(0u), sinA = doubleAt(2u);

  uint node, top, nodes, tests;
  float t0, t1;
  if (phase == 0.0) {
    node = 0u, top = 0u, count = 0u, nodes = 0u, tests = 0u;
    t0 = 0.0, t1 = CONE_INF;
    phase = 1.0;
    vec3 lo = vec3(tree[0], tree[1], tree[2]), hi = vec3(tree[3], tree[4], tree[5]);
    if (uNodeCount == 0u || !coneBox(apex, axis, k, lo, hi, t0, t1)) phase = 2.0;
  } else {
    node = floatBitsToUint(rec[base + 1u]);
    t0 = rec[base + 2u], t1 = rec[base + 3u];
    top = floatBitsToUint(rec[base + 4u]);
    count = floatBitsToUint(rec[base + 5u]);
    nodes = floatBitsToUint(rec[base + 6u]);
    tests = floatBitsToUint(rec[base + 7u]);
  }
  for (int i = 0; i < uLoopLimit && phase == 1.0; ++i) {
    ++nodes;
    uint at5 = uNodeBase + 5u * node;
    float split = tree[at5];
    uint axisOf = bitsAt(at5 + 1u);
    bool next = false;
    if (axisOf != 3u) {
      uint right = bitsAt(at5 + 2u);
      float l0 = t0, l1 = t1, r0 = t0, r1 = t1;
      float cut = cutoff();
      bool goLeft = coneSide(apex, axis, k, axisOf, split, 0u, l0, l1) && l0 <= cut;
      bool goRight = coneSide(apex, axis, k, axisOf, split, 1u, r0, r1) && r0 <= cut;
      if (goLeft && goRight) {
        bool leftFirst = l0 <= r0;
        uint slot = stackBase + 3u * top;
        rec[slot] = uintBitsToFloat(leftFirst ? right : node + 1u);
        rec[slot + 1u] = leftFirst ? r0 : l0;
        rec[slot + 2u] = leftFirst ? r1 : l1;
        ++top;
        node = leftFirst ? node + 1u : right;
        t0 = leftFirst ? l0 : r0, t1 = leftFirst ? l1 : r1;
        next = true;
      } else if (goLeft || goRight) {
        node = goLeft ? node + 1u : right;
        t0 = goLeft ? l0 : r0, t1 = goLeft ? l1 : r1;
        next = true;
      }
    } else {
      uint first = bitsAt(at5 + 3u), refs = bitsAt(at5 + 4u);
      for (uint r = 0u; r < refs && phase == 1.0; ++r) {
        uint id = bitsAt(uRefBase + first + r);
        ++tests;
        uint p = uTriBase + 9u * id;
        dvec3 p0 = dvec3(tree[p], tree[p + 1u], tree[p + 2u]);
        dvec3 p1 = dvec3(tree[p + 3u], tree[p + 4u], tree[p + 5u]);
        dvec3 p2 = dvec3(tree[p + 6u], tree[p + 7u], tree[p + 8u]);
        float t;
        if (coneMeetsTriangle(s, v, cosA, sinA, p0, p1, p2, t) && !insertHit(t, id)) phase = 3.0;
      }
    }
    if (next || phase != 1.0) continue;
    bool found = false;  // pop until an entry that can still hold a nearer hit
    while (top > 0u && !found) {
      --top;
      uint slot = stackBase + 3u * top;
      if (rec[slot + 1u] <= cutoff()) {
        node = floatBitsToUint(rec[slot]), t0 = rec[slot + 1u], t1 = rec[slot + 2u];
        found = true;
      }
    }
    if (!found) phase = 2.0;
  }
  rec[base] = phase;
  rec[base + 1u] = uintBitsToFloat(node);
  rec[base + 2u] = t0;
  rec[base + 3u] = t1;
  rec[base + 4u] = uintBitsToFloat(top);
  rec[base + 5u] = uintBitsToFloat(count);
  rec[base + 6u] = uintBitsToFloat(nodes);
  rec[base + 7u] = uintBitsToFloat(tests);
  outState = vec4(phase);
}
