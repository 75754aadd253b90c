// Cones through kk-bvh's tree as a stream kernel: the steps of
// accel/cone/bvh_cone_traversal.cpp's stack traversal (nearer child first),
// up to uLoopLimit stack entries per pass; the record (cone_record.glsl)
// keeps the stack (node, t0, -) and the sorted hit list across passes. A
// BVH leaf holds one triangle, met once, so no triangle is inserted twice.
// The node-sorted variant (--cone-nodes sorted) is CPU only.
#include "cone/cone_record.glsl"

// The tree: nodes at uNodeBase (box min, box max, triangle, first child,
// child count: 9 floats), the child lists at uRefBase, triangles at uTriBase.

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

  uint top, nodes, tests;
  if (phase == 0.0) {
    top = 0u, count = 0u, nodes = 0u, tests = 0u;
    phase = 1.0;
    float t0 = 0.0, t1 = CONE_INF;
    if (uNodeCount > 0u) {
      uint n = uNodeBase;
      vec3 lo = vec3(tree[n], tree[n + 1u], tree[n + 2u]), hi = vec3(tree[n + 3u], tree[n + 4u], tree[n + 5u]);
      if (coneBox(apex, axis, k, lo, hi, t0, t1)) {
        rec[stackBase] = uintBitsToFloat(0u);
        rec[stackBase + 1u] = t0;
        top = 1u;
      }
    }
  } else {
    top = floatBitsToUint(rec[base + 4u]);
    count = floatBitsToUint(rec[base + 5u]);
    nodes = floatBitsToUint(rec[base + 6u]);
    tests = floatBitsToUint(rec[base + 7u]);
  }
  for (int i = 0; i < uLoopLimit && phase == 1.0 && top > 0u; ++i) {
    --top;
    uint node = floatBitsToUint(rec[stackBase + 3u * top]);
    float entryT0 = rec[stackBase + 3u * top + 1u];
    if (entryT0 > cutoff()) continue;
    ++nodes;
    uint n = uNodeBase + 9u * node;
    uint children = bitsAt(n + 8u);
    if (children == 0u) {
      ++tests;  // one triangle per leaf
      uint id = bitsAt(n + 6u);
      uint p = uTriBase + 9u * id;
      dvec3 p0 = dvec3(tree[p], tree[p + 1u], tree[p + 2u]);
      dvec3 p1 = dvec3(tree[p + 3u], tree[p + 4u], tree[p + 5u]);
      dvec3 p2 = dvec3(tree[p + 6u], tree[p + 7u], tree[p + 8u]);
      float t;
      if (coneMeetsTriangle(s, v, cosA, sinA, p0, p1, p2, t) && !insertHit(t, id)) phase = 3.0;
      continue;
    }
    // The children the cone reaches, pushed farthest first (a stable
    // insertion sort by t0, as std::sort sorts a few entries).
    uint first = bitsAt(n + 7u), pushed = 0u;
    for (uint j = 0u; j < children && pushed < 64u; ++j) {
      uint child = bitsAt(uRefBase + first + j);
      uint m = uNodeBase + 9u * child;
      vec3 lo = vec3(tree[m], tree[m + 1u], tree[m + 2u]), hi = vec3(tree[m + 3u], tree[m + 4u], tree[m + 5u]);
      float c0 = 0.0, c1 = CONE_INF;
      if (!coneBox(apex, axis, k, lo, hi, c0, c1) || !(c0 <= cutoff())) continue;
      uint slot = top + pushed;
      while (slot > top && rec[stackBase + 3u * (slot - 1u) + 1u] < c0) {  // farther first
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
  rec[base] = phase;
  rec[base + 4u] = uintBitsToFloat(top);
  rec[base + 5u] = uintBitsToFloat(count);
  rec[base + 6u] = uintBitsToFloat(nodes);
  rec[base + 7u] = uintBitsToFloat(tests);
  outState = vec4(phase);
}
