// What every cone kernel shares (kd_cone.frag, bvh_cone.frag): the buffers,
// uniforms, the cone's record and its hits.
//
// Record of element e, at float e * uRecordFloats:
//   [0] phase: 0 not started, 1 running, 2 done, 3 its hits overflowed
//   [1] node (uint bits), [2] t0, [3] t1, [4] stack top, [5] hit count,
//   [6] nodes visited, [7] triangle references met, [8] the next reference
//   of a leaf left mid-way, plus one (0: not in a leaf), [9] the nearest hit's t, [10] its id (uint bits)
//   then uStackSize stack entries (node, t0, t1), then the hits:
//   - --cone-max N: the N nearest distinct triangles, sorted by (t, id)
//     (2 floats each);
//   - --cone-max 0: the distinct triangles met, as an open-addressing set of
//     id + 1 (uTableSize slots, 0 = empty), plus the nearest in [9], [10].
//     Nothing but count, nearest id and t leaves the stream path, so the
//     set needs no order, and inserting costs a few probes instead of a
//     shift of the sorted list (thousands of moves at 2.5 degrees).
//
// Work per pass. llvmpipe ends every loop of a shader invocation, silently,
// once all loops of the invocation together have run 65,535 iterations
// (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, shared by all loops and counted
// per SIMD vector). A pass cut there would lose part of a leaf or of a
// list's shift. So each cone counts its own loop iterations (`work`) and
// ends its pass, state saved, before uWorkBudget would be exceeded; the
// host sets the budget so that a whole SIMD vector stays below the cap.
#include "cone/cone_tests.glsl"

layout(std430, binding = 0) buffer ConeRecords { float rec[]; };
// The tree (the kernel's layout; triangles at uTriBase, 9 floats each).
layout(std430, binding = 1) readonly buffer ConeTree { float tree[]; };
// [0..3] cos and sin of the half-angle (double as two words), then per
// element 16 floats: apex, axis, k (Eq. 2's spread), -, the unit axis in
// double (3 x two words).
layout(std430, binding = 2) readonly buffer ConeInputs { float cones[]; };

const uint CONE_HEADER = 12u;

uniform uint uStreamWidth;
uniform uint uElementCount;  // cones in this band; the last row's rest is padding
uniform uint uRecordFloats;
uniform uint uStackSize;
uniform uint uCapacity;   // distinct triangles a --cone-max 0 set may hold
uniform uint uTableSize;  // its slots: a power of two >= 2 uCapacity
uniform uint uMaxHits;
uniform uint uWorkBudget;
uniform uint uNodeCount;
uniform uint uNodeBase;
uniform uint uRefBase;
uniform uint uTriBase;
uniform int uLoopLimit;

layout(location = 0) out vec4 outState;

// The cone's state while a pass runs; loadRecord/storeRecord move it.
uint base, stackBase, hitBase;
float phase, t0, t1;
uint node, top, count, nodes, tests, leafNext, nearId;
float nearT;
uint work;  // loop iterations this pass

// The cone's inputs.
vec3 apex, axis, spread;
dvec3 apexD, axisD;
double cosA, sinA;

uint bitsAt(uint i) { return floatBitsToUint(tree[i]); }

double doubleAt(uint i) { return packDouble2x32(uvec2(floatBitsToUint(cones[i]), floatBitsToUint(cones[i + 1u]))); }

// Reads the cone and record of the element at `at`; phase 0 starts a fresh
// state, and padding beyond the band reads as done.
void loadRecord(uvec2 at) {
  uint e = at.y * uStreamWidth + at.x;
  if (e >= uElementCount) {
    phase = 2.0;
    return;
  }
  base = e * uRecordFloats;
  stackBase = base + CONE_HEADER;
  hitBase = stackBase + 3u * uStackSize;
  uint c = 4u + 16u * e;
  apex = vec3(cones[c], cones[c + 1u], cones[c + 2u]);
  axis = vec3(cones[c + 3u], cones[c + 4u], cones[c + 5u]);
  spread = vec3(cones[c + 6u], cones[c + 7u], cones[c + 8u]);
  apexD = dvec3(apex);
  axisD = dvec3(doubleAt(c + 10u), doubleAt(c + 12u), doubleAt(c + 14u));
  cosA = doubleAt(0u), sinA = doubleAt(2u);
  work = 0u;
  phase = rec[base];
  if (phase == 0.0) {
    node = 0u, top = 0u, count = 0u, nodes = 0u, tests = 0u, leafNext = 0u;
    t0 = 0.0, t1 = CONE_INF;
    nearT = CONE_INF, nearId = 0xFFFFFFFFu;
    return;
  }
  node = floatBitsToUint(rec[base + 1u]);
  t0 = rec[base + 2u], t1 = rec[base + 3u];
  top = floatBitsToUint(rec[base + 4u]);
  count = floatBitsToUint(rec[base + 5u]);
  nodes = floatBitsToUint(rec[base + 6u]);
  tests = floatBitsToUint(rec[base + 7u]);
  leafNext = floatBitsToUint(rec[base + 8u]);
  nearT = rec[base + 9u];
  nearId = floatBitsToUint(rec[base + 10u]);
}

void storeRecord() {
  rec[base] = phase;
  rec[base + 1u] = uintBitsToFloat(node);
  rec[base + 2u] = t0;
  rec[base + 3u] = t1;
  rec[base + 4u] = uintBitsToFloat(top);
  rec[base + 5u] = uintBitsToFloat(count);
  rec[base + 6u] = uintBitsToFloat(nodes);
  rec[base + 7u] = uintBitsToFloat(tests);
  rec[base + 8u] = uintBitsToFloat(leafNext);
  rec[base + 9u] = nearT;
  rec[base + 10u] = uintBitsToFloat(nearId);
  outState = vec4(phase);
}

// (ta, ida) before (tb, idb): nearest first, ties by id (coneHitBefore).
bool hitBefore(float ta, uint ida, float tb, uint idb) { return ta < tb || (ta == tb && ida < idb); }

float hitT(uint i) { return rec[hitBase + 2u * i]; }
uint hitId(uint i) { return floatBitsToUint(rec[hitBase + 2u * i + 1u]); }

// The axis distance beyond which nothing can enter the list: its last
// entry once --cone-max N are kept, else none.
float cutoff() { return uMaxHits > 0u && count == uMaxHits ? hitT(count - 1u) : CONE_INF; }

// The loop iterations one insertHit may take, at most (the set's probes are
// counted as they happen; a few dozen at a load of one half).
uint insertWork() { return uMaxHits > 0u ? uMaxHits + 40u : 64u; }

// Can this pass still test a triangle (5 iterations) and insert it?
bool workLeftForTriangle(uint extra) { return work + extra + 5u + insertWork() <= uWorkBudget; }

// --cone-max N: ConeHitList::insert into the sorted list, without duplicates.
void insertSorted(float t, uint id) {
  if (count == uMaxHits && !hitBefore(t, id, hitT(count - 1u), hitId(count - 1u))) return;
  uint lo = 0u, hi = count;
  while (lo < hi) {  // upper bound: the first entry the hit goes before
    ++work;
    uint mid = (lo + hi) / 2u;
    if (hitBefore(t, id, hitT(mid), hitId(mid))) hi = mid;
    else lo = mid + 1u;
  }
  if (lo > 0u && hitT(lo - 1u) == t && hitId(lo - 1u) == id) return;  // met in an earlier leaf
  uint last = min(count + 1u, uMaxHits);
  for (uint j = last - 1u; j > lo; --j) {
    ++work;
    rec[hitBase + 2u * j] = rec[hitBase + 2u * j - 2u];
    rec[hitBase + 2u * j + 1u] = rec[hitBase + 2u * j - 1u];
  }
  rec[hitBase + 2u * lo] = t;
  rec[hitBase + 2u * lo + 1u] = uintBitsToFloat(id);
  count = last;
}

// --cone-max 0: adds id to the set unless a leaf met it already; false when
// the set is full (every triangle must be kept).
bool insertDistinct(float t, uint id) {
  uint mask = uTableSize - 1u;
  uint slot = (id * 2654435769u) & mask;  // Knuth's multiplicative hash
  uint key = id + 1u;
  for (uint probe = 0u; probe < uTableSize; ++probe) {
    ++work;
    uint held = floatBitsToUint(rec[hitBase + slot]);
    if (held == key) return true;
    if (held == 0u) {
      if (count == uCapacity) return false;
      rec[hitBase + slot] = uintBitsToFloat(key);
      ++count;
      if (hitBefore(t, id, nearT, nearId)) nearT = t, nearId = id;
      return true;
    }
    slot = (slot + 1u) & mask;
  }
  return false;
}

// Tests triangle `id` and keeps it if the cone meets it; false when the
// --cone-max 0 set overflowed.
bool testTriangle(uint id) {
  ++tests;
  work += 5u;  // the exact test's loops over edges and generators
  uint p = uTriBase + 9u * id;
  dvec3 p0 = dvec3(tree[p], tree[p + 1u], tree[p + 2u]);
  dvec3 p1 = dvec3(tree[p + 3u], tree[p + 4u], tree[p + 5u]);
  dvec3 p2 = dvec3(tree[p + 6u], tree[p + 7u], tree[p + 8u]);
  float t;
  if (!coneMeetsTriangle(apexD, axisD, cosA, sinA, p0, p1, p2, t)) return true;
  if (uMaxHits > 0u) {
    insertSorted(t, id);
    return true;
  }
  return insertDistinct(t, id);
}
