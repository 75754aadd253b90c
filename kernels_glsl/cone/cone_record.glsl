// What every cone kernel shares (kd_cone.frag, bvh_cone.frag): the buffers,
// uniforms and the sorted list of distinct hits in the cone's record.
// Record of element e, at float e * (8 + 3 uStackSize + 2 uCapacity):
//   [0] phase: 0 not started, 1 running, 2 done, 3 its list overflowed
//   [1] node (uint bits), [2] t0, [3] t1, [4] stack top, [5] hit count,
//   [6] nodes visited, [7] triangle references met (uint bits)
//   then uStackSize entries (node, t0, t1) and uCapacity hits (t, id):
//   the distinct triangles met, sorted by (t, id).
#include "cone/cone_tests.glsl"

layout(std430, binding = 0) buffer ConeRecords { float rec[]; };
// The tree (the kernel's layout; triangles at uTriBase, 9 floats each).
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

