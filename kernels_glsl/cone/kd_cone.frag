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
#include "cone/cone_tests.glsl"

layout(std430, binding = 0) buffer ConeRecords { float rec[]; };
// The tree: [0..5] root box, nodes at uNodeBase (split, axis, right child,
// first reference, reference count), references at uRefBase, triangles at
// uTriBase (9 floats each).
layout(std430, binding = 1) readonly buffer ConeTree { float tree[]; };
// [0..3] cos and sin of the half-angle (double as two words), then per
// element 16 floats: apex, axis, k (Eq. 2's spread), -, the unit axis in
// double (3 x two words).
layout(std430, binding = 2) readonly buffer ConeInputs { float cones[]; };

uniform uint uStreamWidth;
uniform uint uStackSize;
uniform uint uCapacity;
uniform uint uMaxHits;
uniform uint uNodeCount;
uniform uint uNodeBase;
uniform uint uRefBase;
uniform uint uTriBase;
uniform int uLoopLimit;

layout(location = 0) out vec4 outState;

uint hitBase;
uint count;

uint bitsAt(uint i) { return floatBitsToUint(tree[i]); }

double doubleAt(uint i) { return packDouble2x32(uvec2(floatBitsToUint(cones[i]), floatBitsToUint(cones[i + 1u]))); }

// (ta, ida) before (tb, idb): nearest first, ties by id (coneHitBefore).
bool hitBefore(float ta, uint ida, float tb, uint idb) { return ta < tb || (ta == tb && ida < idb); }

float hitT(uint i) { return rec[hitBase + 2u * i]; }
uint hitId(uint i) { return floatBitsToUint(rec[hitBase + 2u * i + 1u]); }

float cutoff() { return uMaxHits > 0u && count == uMaxHits ? hitT(count - 1u) : CONE_INF; }

// ConeHitList::insert without duplicates; false when the list is full with
// --cone-max 0 (every triangle must be kept).
bool insertHit(float t, uint id) {
  if (uMaxHits > 0u && count == uMaxHits && !hitBefore(t, id, hitT(count - 1u), hitId(count - 1u))) return true;
  uint lo = 0u, hi = count;
  while (lo < hi) {  // upper bound: the first entry the hit goes before
    uint mid = (lo + hi) / 2u;
    if (hitBefore(t, id, hitT(mid), hitId(mid))) hi = mid;
    else lo = mid + 1u;
  }
  if (lo > 0u && hitT(lo - 1u) == t && hitId(lo - 1u) == id) return true;  // met in an earlier leaf
  uint limit = uMaxHits > 0u ? uMaxHits : uCapacity;
  if (uMaxHits == 0u && count == uCapacity) return false;
  uint last = min(count + 1u, limit);
  for (uint j = last - 1u; j > lo; --j) {
    rec[hitBase + 2u * j] = rec[hitBase + 2u * j - 2u];
    rec[hitBase + 2u * j + 1u] = rec[hitBase + 2u * j - 1u];
  }
  rec[hitBase + 2u * lo] = t;
  rec[hitBase + 2u * lo + 1u] = uintBitsToFloat(id);
  count = last;
  return true;
}

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
