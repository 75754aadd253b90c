// The wide BVH's traversal with AVX2: eight slab tests per instruction, four
// Möller–Trumbore tests per instruction (in packets' leaves, where eight rays
// arrive together, one triangle against eight rays). Only the functions here carry the
// target attribute (the rest of the build stays portable); the caller checks
// wideBvhAvx2Available() first. No fused multiply-add: the results must equal
// the scalar build's and geometry.h's to the bit.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "accel/wide_bvh/wide_bvh_traversal.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

namespace passtrace {
namespace {

#define WIDE_TARGET __attribute__((target("avx2")))
// The node and pack tests inlined into the loops (GCC kept them as calls: 9 % of a frame in the call alone).
#define WIDE_INLINE inline __attribute__((always_inline))

struct RayPre;
WIDE_TARGET WIDE_INLINE uint32_t boxTest8(const WideBvhNode& node, const RayPre& pre, float tBest, float* tNear);
WIDE_TARGET WIDE_INLINE uint32_t packTest4(const TrianglePack& pack, const RayPre& pre, float tBest, float* t, float* u,
                               float* v);

#include "accel/wide_bvh/wide_bvh_traverse.inc"

// The slab test's verdict, lane by lane, from each axis's entry (s) and exit
// (l) distance: geometry.h's intersectsBox. `near` gets the entry distances;
// returns all-ones in the lanes whose box is hit before tBest.
WIDE_TARGET WIDE_INLINE __m256 slabVerdict(const __m256 (&s)[3], const __m256 (&l)[3], __m256 tBest, __m256& near) {
  near = _mm256_max_ps(_mm256_max_ps(s[0], s[1]), s[2]);
  const __m256 exit = _mm256_mul_ps(_mm256_min_ps(_mm256_min_ps(l[0], l[1]), l[2]), _mm256_set1_ps(kRobustExitScale));
  return _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(near, exit, _CMP_LE_OQ),
                                     _mm256_cmp_ps(exit, _mm256_setzero_ps(), _CMP_GE_OQ)),
                       _mm256_cmp_ps(near, tBest, _CMP_LT_OQ));
}

// All-ones in the lanes whose bit is set in `bits` (bit i: lane i).
WIDE_TARGET WIDE_INLINE __m256i laneMask(uint32_t bits) {
  const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(bits)), bit), bit);
}

// The eight slab tests as vectors: entry distances and the all-ones lanes of the boxes hit.
WIDE_TARGET WIDE_INLINE void boxTest8v(const WideBvhNode& node, const RayPre& pre, float tBest, __m256& near,
                                       __m256& hit) {
  const float* bounds = reinterpret_cast<const float*>(&node);  // minX[8], maxX[8], minY[8], ... (wide_bvh.h)
  __m256 s[3], l[3];
  for (int k = 0; k < 3; ++k) {
    const __m256 o = _mm256_set1_ps(pre.o[k]), inv = _mm256_set1_ps(pre.inv[k]);
    // The slab the ray enters first is known from the direction's sign: rounding
    // is monotonic, so (min - o) inv <= (max - o) inv for inv > 0 and the
    // scalar build's min/max of the two picks the same values (up to the sign
    // of a zero, which no comparison sees).
    s[k] = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(bounds + pre.nearAt[k]), o), inv);
    l[k] = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(bounds + pre.farAt[k]), o), inv);
  }
  if (pre.anyParallel)  // rare: axis-parallel rays
    for (int k = 0; k < 3; ++k) {
      if (!pre.parallel[k]) continue;
      const __m256 o = _mm256_set1_ps(pre.o[k]);
      const __m256 lower = _mm256_load_ps(bounds + 16 * k), upper = _mm256_load_ps(bounds + 16 * k + 8);
      const __m256 inside = _mm256_and_ps(_mm256_cmp_ps(o, lower, _CMP_GE_OQ), _mm256_cmp_ps(o, upper, _CMP_LE_OQ));
      const __m256 inf = _mm256_set1_ps(kInfinity), minusInf = _mm256_set1_ps(-kInfinity);
      s[k] = _mm256_blendv_ps(inf, minusInf, inside);
      l[k] = _mm256_blendv_ps(minusInf, inf, inside);
    }
  hit = slabVerdict(s, l, _mm256_set1_ps(tBest), near);
}

WIDE_TARGET WIDE_INLINE uint32_t boxTest8(const WideBvhNode& node, const RayPre& pre, float tBest, float* tNear) {
  __m256 near, hit;
  boxTest8v(node, pre, tBest, near, hit);
  _mm256_storeu_ps(tNear, near);
  return uint32_t(_mm256_movemask_ps(hit));
}

// (a.x b.x + a.y b.y) + a.z b.z, glm::dot's order.
WIDE_TARGET inline __m128 dot(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}

WIDE_TARGET WIDE_INLINE uint32_t packTest4(const TrianglePack& k, const RayPre& pre, float tBest, float* t, float* u,
                                           float* v) {
  const __m128 dx = _mm_set1_ps(pre.d[0]), dy = _mm_set1_ps(pre.d[1]), dz = _mm_set1_ps(pre.d[2]);
  const __m128 e1x = _mm_load_ps(k.e1x), e1y = _mm_load_ps(k.e1y), e1z = _mm_load_ps(k.e1z);
  const __m128 e2x = _mm_load_ps(k.e2x), e2y = _mm_load_ps(k.e2y), e2z = _mm_load_ps(k.e2z);
  const __m128 px = _mm_sub_ps(_mm_mul_ps(dy, e2z), _mm_mul_ps(e2y, dz));
  const __m128 py = _mm_sub_ps(_mm_mul_ps(dz, e2x), _mm_mul_ps(e2z, dx));
  const __m128 pz = _mm_sub_ps(_mm_mul_ps(dx, e2y), _mm_mul_ps(e2x, dy));
  const __m128 det = dot(px, py, pz, e1x, e1y, e1z);
  const __m128 invDet = _mm_div_ps(_mm_set1_ps(1.0f), det);
  const __m128 tx = _mm_sub_ps(_mm_set1_ps(pre.o[0]), _mm_load_ps(k.v0x));
  const __m128 ty = _mm_sub_ps(_mm_set1_ps(pre.o[1]), _mm_load_ps(k.v0y));
  const __m128 tz = _mm_sub_ps(_mm_set1_ps(pre.o[2]), _mm_load_ps(k.v0z));
  const __m128 uu = _mm_mul_ps(dot(px, py, pz, tx, ty, tz), invDet);
  const __m128 qx = _mm_sub_ps(_mm_mul_ps(ty, e1z), _mm_mul_ps(e1y, tz));
  const __m128 qy = _mm_sub_ps(_mm_mul_ps(tz, e1x), _mm_mul_ps(e1z, tx));
  const __m128 qz = _mm_sub_ps(_mm_mul_ps(tx, e1y), _mm_mul_ps(e1x, ty));
  const __m128 vv = _mm_mul_ps(dot(qx, qy, qz, dx, dy, dz), invDet);
  const __m128 tt = _mm_mul_ps(dot(qx, qy, qz, e2x, e2y, e2z), invDet);
  const __m128 zero = _mm_setzero_ps();
  __m128 hit = _mm_and_ps(_mm_cmp_ps(det, zero, _CMP_NEQ_OQ), _mm_cmp_ps(uu, zero, _CMP_GE_OQ));
  hit = _mm_and_ps(hit, _mm_cmp_ps(vv, zero, _CMP_GE_OQ));
  hit = _mm_and_ps(hit, _mm_cmp_ps(_mm_add_ps(uu, vv), _mm_set1_ps(1.0f), _CMP_LE_OQ));
  hit = _mm_and_ps(hit, _mm_cmp_ps(tt, zero, _CMP_GT_OQ));
  hit = _mm_and_ps(hit, _mm_cmp_ps(tt, _mm_set1_ps(tBest), _CMP_LT_OQ));
  _mm_storeu_ps(t, tt);
  _mm_storeu_ps(u, uu);
  _mm_storeu_ps(v, vv);
  return uint32_t(_mm_movemask_ps(hit));
}

// The same, for eight rays.
WIDE_TARGET WIDE_INLINE __m256 dot(__m256 ax, __m256 ay, __m256 az, __m256 bx, __m256 by, __m256 bz) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)), _mm256_mul_ps(az, bz));
}

// One triangle of a pack against eight rays (the packet's columns): the same
// operations as packTest4 for each pair of ray and triangle, so the same bits.
WIDE_TARGET WIDE_INLINE __m256 triangleTest8(const TrianglePack& k, int i, const __m256 (&o)[3], const __m256 (&d)[3],
                                             __m256 tBest, __m256& t, __m256& u, __m256& v) {
  const __m256 e1x = _mm256_set1_ps(k.e1x[i]), e1y = _mm256_set1_ps(k.e1y[i]), e1z = _mm256_set1_ps(k.e1z[i]);
  const __m256 e2x = _mm256_set1_ps(k.e2x[i]), e2y = _mm256_set1_ps(k.e2y[i]), e2z = _mm256_set1_ps(k.e2z[i]);
  const __m256 px = _mm256_sub_ps(_mm256_mul_ps(d[1], e2z), _mm256_mul_ps(e2y, d[2]));
  const __m256 py = _mm256_sub_ps(_mm256_mul_ps(d[2], e2x), _mm256_mul_ps(e2z, d[0]));
  const __m256 pz = _mm256_sub_ps(_mm256_mul_ps(d[0], e2y), _mm256_mul_ps(e2x, d[1]));
  const __m256 det = dot(px, py, pz, e1x, e1y, e1z);
  const __m256 invDet = _mm256_div_ps(_mm256_set1_ps(1.0f), det);
  const __m256 tx = _mm256_sub_ps(o[0], _mm256_set1_ps(k.v0x[i]));
  const __m256 ty = _mm256_sub_ps(o[1], _mm256_set1_ps(k.v0y[i]));
  const __m256 tz = _mm256_sub_ps(o[2], _mm256_set1_ps(k.v0z[i]));
  u = _mm256_mul_ps(dot(px, py, pz, tx, ty, tz), invDet);
  const __m256 qx = _mm256_sub_ps(_mm256_mul_ps(ty, e1z), _mm256_mul_ps(e1y, tz));
  const __m256 qy = _mm256_sub_ps(_mm256_mul_ps(tz, e1x), _mm256_mul_ps(e1z, tx));
  const __m256 qz = _mm256_sub_ps(_mm256_mul_ps(tx, e1y), _mm256_mul_ps(e1x, ty));
  v = _mm256_mul_ps(dot(qx, qy, qz, d[0], d[1], d[2]), invDet);
  t = _mm256_mul_ps(dot(qx, qy, qz, e2x, e2y, e2z), invDet);
  const __m256 zero = _mm256_setzero_ps();
  __m256 hit = _mm256_and_ps(_mm256_cmp_ps(det, zero, _CMP_NEQ_OQ), _mm256_cmp_ps(u, zero, _CMP_GE_OQ));
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(v, zero, _CMP_GE_OQ));
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_add_ps(u, v), _mm256_set1_ps(1.0f), _CMP_LE_OQ));
  hit = _mm256_and_ps(hit, _mm256_cmp_ps(t, zero, _CMP_GT_OQ));
  return _mm256_and_ps(hit, _mm256_cmp_ps(t, tBest, _CMP_LT_OQ));
}

// Eight rows of eight lanes to eight columns: out[r] holds lane r of every in[i].
WIDE_TARGET WIDE_INLINE void transpose8(const __m256 (&in)[8], __m256 (&out)[8]) {
  __m256 pairs[8], quads[8];
  for (int i = 0; i < 8; i += 2) {  // lanes 0,1 | 4,5 and 2,3 | 6,7 of rows i and i + 1, interleaved
    pairs[i] = _mm256_unpacklo_ps(in[i], in[i + 1]);
    pairs[i + 1] = _mm256_unpackhi_ps(in[i], in[i + 1]);
  }
  for (int i = 0; i < 8; i += 4) {  // one lane of rows i .. i + 3 in each 128-bit half
    quads[i] = _mm256_shuffle_ps(pairs[i], pairs[i + 2], 0x44);
    quads[i + 1] = _mm256_shuffle_ps(pairs[i], pairs[i + 2], 0xEE);
    quads[i + 2] = _mm256_shuffle_ps(pairs[i + 1], pairs[i + 3], 0x44);
    quads[i + 3] = _mm256_shuffle_ps(pairs[i + 1], pairs[i + 3], 0xEE);
  }
  for (int r = 0; r < 4; ++r) {
    out[r] = _mm256_permute2f128_ps(quads[r], quads[r + 4], 0x20);
    out[r + 4] = _mm256_permute2f128_ps(quads[r], quads[r + 4], 0x31);
  }
}

// prepare() for a whole packet, eight rays per step: the same operations lane
// by lane (IEEE division rounds alike in every lane), each ray's 64-byte
// RayPre then written as two 32-byte rows of a transpose. Ray by ray it took
// 94 instructions per ray, a seventh of a bunny primary frame. Also sets
// tBest to the rays' tMax, and -inf in the lanes past the packet's end
// (never live). `pre` has room for the packet rounded up to eight rays.
// With kAcross, for nodeAcrossRays, it also keeps the inverse directions as
// columns, sets bit g of oneOctant when the rays of group g of eight all point
// into one octant and returns the rays with an axis-parallel slab (bit r: ray r).
static_assert(sizeof(RayPre) == 64 && offsetof(RayPre, d) == 12 && offsetof(RayPre, inv) == 24 &&
                  offsetof(RayPre, parallel) == 36 && offsetof(RayPre, anyParallel) == 39 &&
                  offsetof(RayPre, nearAt) == 40 && offsetof(RayPre, farAt) == 52,
              "preparePacket writes RayPre as 16 four-byte columns");
template <bool kAcross>
WIDE_TARGET uint64_t preparePacket(const RayPacket& packet, RayPre* pre, float* tBest,
                                   float (&invColumns)[3][kWidePacketMax], uint32_t& oneOctant) {
  uint64_t parallelRays = 0;
  oneOctant = 0;
  const __m256 tiny = _mm256_set1_ps(1e-20f), zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 magnitude = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const float* origin[3] = {packet.ox, packet.oy, packet.oz};
  const float* direction[3] = {packet.dx, packet.dy, packet.dz};
  for (int first = 0; first < packet.count; first += 8) {
    const int n = std::min(8, packet.count - first);
    const __m256i in = _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    __m256 column[16];  // RayPre's fields in memory order, one ray per lane
    __m256i flags = _mm256_setzero_si256(), anyParallel = _mm256_setzero_si256();
    const uint32_t rays = (1u << n) - 1u;
    bool sameOctant = true;
    for (int k = 0; k < 3; ++k) {
      const __m256 d = _mm256_maskload_ps(direction[k] + first, in);
      // safeInverse: a component below 1e-20 in magnitude stands in as +-1e-20 (+ for -0).
      const __m256 small = _mm256_cmp_ps(_mm256_and_ps(d, magnitude), tiny, _CMP_LT_OQ);
      const __m256 signedTiny = _mm256_blendv_ps(tiny, _mm256_sub_ps(zero, tiny), _mm256_cmp_ps(d, zero, _CMP_LT_OQ));
      const __m256 inv = _mm256_div_ps(one, _mm256_blendv_ps(d, signedTiny, small));
      const __m256i parallel = _mm256_srli_epi32(_mm256_castps_si256(_mm256_cmp_ps(
                                                     _mm256_and_ps(inv, magnitude), _mm256_set1_ps(kParallelInverse),
                                                     _CMP_GT_OQ)),
                                                 31);  // 0 or 1
      const __m256i positive = _mm256_castps_si256(_mm256_cmp_ps(inv, zero, _CMP_GT_OQ));
      if constexpr (kAcross) {
        const uint32_t signs = uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(positive))) & rays;
        sameOctant = sameOctant && (signs == 0 || signs == rays);
        _mm256_store_ps(invColumns[k] + first, inv);
      }
      const __m256i slab = _mm256_set1_epi32(16 * k), maxArray = _mm256_set1_epi32(8);  // bounds + 8: the max array
      column[k] = _mm256_maskload_ps(origin[k] + first, in);
      column[3 + k] = d;
      column[6 + k] = inv;
      column[10 + k] = _mm256_castsi256_ps(_mm256_add_epi32(slab, _mm256_andnot_si256(positive, maxArray)));
      column[13 + k] = _mm256_castsi256_ps(_mm256_add_epi32(slab, _mm256_and_si256(positive, maxArray)));
      flags = _mm256_or_si256(flags, _mm256_slli_epi32(parallel, 8 * k));  // the bool parallel[k]
      anyParallel = _mm256_or_si256(anyParallel, parallel);
    }
    column[9] = _mm256_castsi256_ps(_mm256_or_si256(flags, _mm256_slli_epi32(anyParallel, 24)));
    if constexpr (kAcross) {
      oneOctant |= uint32_t(sameOctant) << (first / 8);
      parallelRays |= uint64_t(uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_slli_epi32(anyParallel, 31)))) &
                               rays)
                      << first;
    }
    __m256 rows[2][8];
    transpose8(*reinterpret_cast<const __m256(*)[8]>(column), rows[0]);
    transpose8(*reinterpret_cast<const __m256(*)[8]>(column + 8), rows[1]);
    for (int r = 0; r < 8; ++r) {
      float* out = reinterpret_cast<float*>(pre + first + r);
      _mm256_storeu_ps(out, rows[0][r]);
      _mm256_storeu_ps(out + 8, rows[1][r]);
    }
    _mm256_store_ps(tBest + first, _mm256_blendv_ps(_mm256_set1_ps(-kInfinity),
                                                    _mm256_maskload_ps(packet.tMax + first, in), _mm256_castsi256_ps(in)));
  }
  return parallelRays;
}

// An inner node, one child at a time, against the live rays (`lanes`) of the
// packet's group g of eight, whose rays all point into one octant, so they
// share the slabs they enter first (`pre`'s nearAt and farAt, those of any of
// them): the classic packet layout, as leafAcrossRays is for leaves. Per pair
// of ray and child it computes boxTest8v's values, so the same bits. Rays with
// an axis-parallel slab are not given here. ORs each child's hit rays into
// raysOf and counts the step for every live ray. Any-hit packets only: a
// closest-hit packet also needs each child's least entry distance, a
// horizontal minimum per child, and took 1-4 % longer with it.
template <typename Mask>
WIDE_TARGET WIDE_INLINE void nodeAcrossRays(const WideBvhNode& node, const RayPacket& rays,
                                            const float (&inv)[3][kWidePacketMax], const RayPre& pre, int g,
                                            uint32_t lanes, const float* tBest, uint32_t* steps,
                                            Mask (&raysOf)[8]) {
  const int at = 8 * g;
  const __m256i live = laneMask(lanes);
  __m256i* counts = reinterpret_cast<__m256i*>(steps + at);
  _mm256_store_si256(counts, _mm256_sub_epi32(_mm256_load_si256(counts), live));  // live lanes are -1
  const __m256 o[3] = {_mm256_load_ps(rays.ox + at), _mm256_load_ps(rays.oy + at), _mm256_load_ps(rays.oz + at)};
  const __m256 iv[3] = {_mm256_load_ps(inv[0] + at), _mm256_load_ps(inv[1] + at), _mm256_load_ps(inv[2] + at)};
  const __m256 tB = _mm256_load_ps(tBest + at);
  const float* bounds = reinterpret_cast<const float*>(&node);  // minX[8], maxX[8], minY[8], ... (wide_bvh.h)
  for (int c = 0; c < kWideBvhWidth; ++c) {
    if (node.child[c] == kWideEmpty) continue;
    __m256 s[3], l[3];
    for (int k = 0; k < 3; ++k) {
      s[k] = _mm256_mul_ps(_mm256_sub_ps(_mm256_broadcast_ss(bounds + pre.nearAt[k] + c), o[k]), iv[k]);
      l[k] = _mm256_mul_ps(_mm256_sub_ps(_mm256_broadcast_ss(bounds + pre.farAt[k] + c), o[k]), iv[k]);
    }
    __m256 near;
    const __m256 hit = _mm256_and_ps(slabVerdict(s, l, tB, near), _mm256_castsi256_ps(live));
    // No branch on the result: whether a child is hit is what a predictor cannot guess.
    raysOf[c] |= Mask(uint32_t(_mm256_movemask_ps(hit))) << at;
  }
}

// A leaf's triangles, one at a time, against the live rays (`lanes`) of the
// packet's group g of eight. Each ray performs packTest4's operations on the
// same triangles, so it finds the same nearest hit (the first in pack order
// on ties, as there) and counts the same tests; an any-hit ray stops at the
// first triangle it hits, where packTest4 would finish that pack. Returns the
// any-hit rays that found a hit.
template <bool kAnyHit>
WIDE_TARGET WIDE_INLINE uint32_t leafAcrossRays(const WideBvh& bvh, uint32_t first, uint32_t packs,
                                                const uint32_t* real, const RayPacket& rays, int g, uint32_t lanes,
                                                float* tBest, Hit* best, uint32_t* tests) {
  const int at = 8 * g;
  // Whole groups of eight lanes: RayPacket initialises its arrays, and masked
  // loads made the traversal 9-53 % slower on this CPU. Lanes outside `lanes`
  // compute results that are never read back.
  const __m256 o[3] = {_mm256_load_ps(rays.ox + at), _mm256_load_ps(rays.oy + at), _mm256_load_ps(rays.oz + at)};
  const __m256 d[3] = {_mm256_load_ps(rays.dx + at), _mm256_load_ps(rays.dy + at), _mm256_load_ps(rays.dz + at)};
  __m256 tB = _mm256_load_ps(tBest + at);  // preparePacket wrote every lane of the group
  __m256i* counts = reinterpret_cast<__m256i*>(tests + at);
  uint32_t done = 0;
  for (uint32_t p = 0; p < packs && done != lanes; ++p) {
    const TrianglePack& pack = bvh.packs[first + p];
    const __m256i looking = laneMask(lanes & ~done);
    _mm256_store_si256(counts, _mm256_add_epi32(_mm256_load_si256(counts),
                                                _mm256_and_si256(looking, _mm256_set1_epi32(int(real[p])))));
    for (int i = 0; i < kTrianglePackWidth; ++i) {
      if (pack.id[i] == kNoHit) continue;
      __m256 t, u, v;
      const __m256 hitLanes = triangleTest8(pack, i, o, d, tB, t, u, v);
      uint32_t hit = uint32_t(_mm256_movemask_ps(hitLanes)) & lanes & ~done;
      if (!hit) continue;
      alignas(32) float ts[8], us[8], vs[8];
      _mm256_store_ps(ts, t), _mm256_store_ps(us, u), _mm256_store_ps(vs, v);
      tB = _mm256_blendv_ps(tB, t, hitLanes);
      if constexpr (kAnyHit) done |= hit;
      for (; hit; hit &= hit - 1) {
        const int lane = __builtin_ctz(hit);
        best[at + lane] = Hit{ts[lane], us[lane], vs[lane], pack.id[i]}, tBest[at + lane] = ts[lane];
      }
    }
  }
  return done;
}

// A packet of up to 32 (Mask = uint32_t) or 64 rays (uint64_t: measured
// slower for 32-ray packets, so both are built) through one shared stack: a child is visited
// when any live ray of the packet hits its box, and only by the rays that hit
// it (per-entry ray masks). Each ray performs the same box and pack tests as
// its single-ray traversal would at the nodes it visits, so its hit is the
// same up to ties in t (the visiting order is the packet's). With
// PacketConfig::singleRayAt, the last few rays at a node finish its subtree
// alone (SingleWalk, taking turns): the same tests again, in single-ray order. With
// PacketConfig::acrossRaysAt, groups of eight test leaves across their rays
// (leafAcrossRays): the same arithmetic, one triangle at a time. With
// PacketConfig::nodesAcrossAt (any-hit packets), groups of eight in one octant
// test inner nodes across their rays (nodeAcrossRays): the same arithmetic,
// one child at a time.
template <typename Mask>
struct PacketEntry {
  uint32_t ref;
  float tNear;  // the least entry distance of those rays (closest-hit packets; any-hit ones do not keep it)
  Mask rays;    // bit r: ray r hit this child's box
};

// The lines a visit of `ref` will read: an inner node's, or a leaf's packs.
WIDE_TARGET WIDE_INLINE void prefetchVisit(const WideBvh& bvh, uint32_t ref) {
  const char* begin;
  size_t bytes;
  if (wideIsLeaf(ref)) {
    begin = reinterpret_cast<const char*>(&bvh.packs[wideLeafFirst(ref)]);
    bytes = wideLeafPacks(ref) * sizeof(TrianglePack);
  } else {
    begin = reinterpret_cast<const char*>(&bvh.nodes[ref]);
    bytes = sizeof(WideBvhNode);
  }
  const uintptr_t first = reinterpret_cast<uintptr_t>(begin) & ~uintptr_t(63);
  for (uintptr_t line = first; line < reinterpret_cast<uintptr_t>(begin) + bytes; line += 64)
    _mm_prefetch(reinterpret_cast<const char*>(line), _MM_HINT_T0);
}

// One ray's walk of a subtree, a visit at a time: traverseSubtree's tests in
// its order, so the same hit and counts.
struct SingleWalk {
  int ray;
  StackEntry entry;  // visited next
  StackEntry* stack;
  int top;
};

// Visits w.entry; false when the walk is over.
template <bool kAnyHit>
WIDE_TARGET WIDE_INLINE bool singleStep(const WideBvh& bvh, const RayPre& pre, Hit& best, uint32_t& steps,
                                        uint32_t& tests, SingleWalk& w) {
  if (!wideIsLeaf(w.entry.ref)) {
    ++steps;
    const WideBvhNode& node = bvh.nodes[w.entry.ref];
    float tNear[8];
    uint32_t mask = boxTest8(node, pre, best.t, tNear);
    StackEntry hits[8];
    int count = 0;
    while (mask) {  // sorted by entry distance as traverseSubtree sorts them
      const int lane = __builtin_ctz(mask);
      mask &= mask - 1;
      StackEntry e{node.child[lane], tNear[lane]};
      int j = count++;
      while (!kAnyHit && j > 0 && hits[j - 1].tNear > e.tNear) {
        hits[j] = hits[j - 1];
        --j;
      }
      hits[j] = e;
    }
    if (count > 0) {
      for (int i = count; i-- > 1;) w.stack[w.top++] = hits[i];
      w.entry = hits[0];
      return true;
    }
  } else {
    const uint32_t first = wideLeafFirst(w.entry.ref), packs = wideLeafPacks(w.entry.ref);
    for (uint32_t p = first; p < first + packs; ++p) {
      const TrianglePack& pack = bvh.packs[p];
      float t[4], u[4], v[4];
      uint32_t mask = packTest4(pack, pre, best.t, t, u, v);
      for (int l = 0; l < kTrianglePackWidth; ++l) tests += pack.id[l] != kNoHit;
      while (mask) {
        const int lane = __builtin_ctz(mask);
        mask &= mask - 1;
        if (t[lane] < best.t) best = Hit{t[lane], u[lane], v[lane], pack.id[lane]};
      }
      if (kAnyHit && best.found()) return false;
    }
  }
  while (w.top > 0) {  // entries a nearer hit found since they were pushed are skipped
    w.entry = w.stack[--w.top];
    if (w.entry.tNear < best.t) return true;
  }
  return false;
}

// One packet's walk, a visit at a time (step), so that several packets can
// take turns: while one visits a node, the lines of the others' next visits
// arrive (tracePackets).
template <typename Mask, bool kAnyHit, bool kTakeTurns>
class PacketWalk {
public:
  using Entry = PacketEntry<Mask>;
  static constexpr bool kWide = sizeof(Mask) == 8;

  WIDE_TARGET void start(const WideBvh& bvh, const PacketJob& job, const PacketConfig& config) {
    bvh_ = &bvh, rays_ = job.rays, config_ = &config, best_ = job.hits, stats_ = job.stats;
    const int count = rays_->count;
    std::fill_n(steps_, kWidePacketMax, 0u);
    std::fill_n(tests_, kWidePacketMax, 0u);
    uint32_t oneOctant = 0;  // groups of eight whose rays share an octant
    const auto parallelRays = Mask(preparePacket<kAnyHit>(*rays_, pre_, tBest_, inv_, oneOctant));
    // The rays nodeAcrossRays may take: those of one-octant groups without an axis-parallel slab.
    acrossCandidates_ = 0;
    if (kAnyHit && config.nodesAcrossAt > 0)
      for (int g = 0; 8 * g < count; ++g)
        if (oneOctant >> g & 1u) acrossCandidates_ |= Mask(0xFF) << (8 * g);
    acrossCandidates_ &= ~parallelRays;
    for (int r = 0; r < count; ++r) best_[r] = Hit{tBest_[r]};
    top_ = 0;
    if (bvh.nodes.empty()) return;
    stack_ = local_;
    if (bvh.stackSize() > std::size(local_)) {
      heap_.resize(bvh.stackSize());
      stack_ = heap_.data();
    }
    // Rays still looking (shadow rays stop at their first hit).
    alive_ = count >= int(8 * sizeof(Mask)) ? ~Mask(0) : (Mask(1) << count) - 1u;
    stack_[top_++] = Entry{0u, -kInfinity, alive_};
    singles_ = 0;
    if (kTakeTurns && singleStacks_.size() < size_t(config.singleRayAt) * bvh.stackSize())
      singleStacks_.resize(size_t(config.singleRayAt) * bvh.stackSize());
  }
  bool done() const { return top_ == 0 && singles_ == 0; }
  // The node or leaf step() visits next (not done()).
  uint32_t next() const { return singles_ > 0 ? single_[turn_].entry.ref : stack_[top_ - 1].ref; }
  // Adds the rays' counts to their stats.
  void finish() const {
    for (int r = 0; r < rays_->count; ++r) {
      stats_[r].steps += steps_[r] + tests_[r];
      stats_[r].triangleTests += tests_[r];
    }
  }

  // Pops the stack's top entry and visits it with the rays it still matters
  // to, or while rays walk a subtree alone, visits the next one's entry.
  WIDE_TARGET void step() {
    if (singles_ > 0) {
      stepSingles();
      return;
    }
    const WideBvh& bvh = *bvh_;
    const RayPacket& rays = *rays_;
    const PacketConfig& config = *config_;
    Hit* best = best_;
    RayPre* pre = pre_;
    float* tBest = tBest_;
    uint32_t *steps = steps_, *tests = tests_;
    Entry* stack = stack_;
    int& top = top_;
    Mask& alive = alive_;
    const Mask acrossCandidates = acrossCandidates_;
    const float(&inv)[3][kWidePacketMax] = inv_;
    const Entry entry = stack[--top];
    // Rays with a hit nearer than the entry distance of every ray here skip
    // it: compared eight at a time, only in the groups of eight that hold
    // some of the entry's rays (deep in the tree an AO packet's entries hold few).
    // Not for any-hit rays: one keeps its tMax until it stops, and it entered
    // this box before that (entry < tMax), so the compare would keep every one
    // (shadow rays 4-12 % and AO rays 3-8 % faster without it and the entry
    // distance's upkeep, docs/bench-speed/NOTES.md).
    Mask live = entry.rays & alive;
    if constexpr (!kAnyHit) {
      Mask nearer = 0;
      const __m256 tNear = _mm256_set1_ps(entry.tNear);
      for (Mask left = live; left;) {
        const int first = __builtin_ctzll(left) & ~7;
        nearer |= Mask(uint32_t(_mm256_movemask_ps(_mm256_cmp_ps(tNear, _mm256_load_ps(tBest + first), _CMP_LT_OQ))))
                  << first;
        left &= ~(Mask(0xFF) << first);
      }
      live &= nearer;
    }
    if (!live) return;
    if (!wideIsLeaf(entry.ref) && __builtin_popcountll(live) <= config.singleRayAt) {
      // Their other entries stay on the packet's stack: a subtree is walked once per ray either way.
      if constexpr (!kTakeTurns) {
        for (Mask m = live; m;) {
          const int r = __builtin_ctzll(m);
          m &= m - 1;
          traverseSubtree(bvh, {}, rays.ray(r), pre[r], entry.ref, kAnyHit, TriangleTest::MollerTrumbore, best[r],
                          steps[r], tests[r]);
          tBest[r] = best[r].t;
          if (kAnyHit && best[r].found()) alive &= ~(Mask(1) << r);
        }
        if (!alive) top = 0;  // every ray has stopped
        return;
      }
      // Taking turns, the rays walk it a visit at a time (stepSingles), the packet's stack waiting until all are done.
      for (Mask m = live; m;) {
        const int r = __builtin_ctzll(m);
        m &= m - 1;
        single_[singles_] = SingleWalk{r, StackEntry{entry.ref, -kInfinity},
                                       singleStacks_.data() + size_t(singles_) * bvh.stackSize(), 0};
        ++singles_;
      }
      turn_ = 0;
      return;
    }
    if (!wideIsLeaf(entry.ref)) {
      const WideBvhNode& node = bvh.nodes[entry.ref];
      // Groups of eight with enough live rays test the node one child against
      // their rays at once; the others, each ray against the eight children.
      Mask perRay = live, acrossRays[8];
      bool anyAcross = false;
      for (Mask left = live & acrossCandidates; left;) {
        const int g = __builtin_ctzll(left) >> 3;
        const Mask group = left & (Mask(0xFF) << (8 * g));
        left &= ~group;
        if (__builtin_popcountll(group) < config.nodesAcrossAt) continue;
        if (!anyAcross) std::fill(acrossRays, acrossRays + 8, Mask(0));
        anyAcross = true;
        perRay &= ~group;
        nodeAcrossRays<Mask>(node, rays, inv, pre[8 * g], g, uint32_t(uint64_t(group) >> (8 * g)), tBest, steps,
                             acrossRays);
      }
      // The rays' bits per child (64-ray packets: rays 0-31, then 32-63).
      __m256i childRays = _mm256_setzero_si256(), childRaysHigh = _mm256_setzero_si256();
      __m256 childNear = _mm256_set1_ps(kInfinity);
      for (Mask m = perRay; m;) {
        const int r = __builtin_ctzll(m);
        m &= m - 1;
        ++steps[r];
        __m256 near, hit;
        boxTest8v(node, pre[r], tBest[r], near, hit);
        const __m256i bit = _mm256_and_si256(_mm256_castps_si256(hit), _mm256_set1_epi32(int(1u << (r & 31))));
        if (!kWide || r < 32)
          childRays = _mm256_or_si256(childRays, bit);
        else
          childRaysHigh = _mm256_or_si256(childRaysHigh, bit);
        if constexpr (!kAnyHit) childNear = _mm256_min_ps(childNear, _mm256_blendv_ps(childNear, near, hit));
      }
      alignas(32) uint32_t raysLow[8], raysHigh[8] = {};
      alignas(32) float nearOf[8];
      _mm256_store_si256(reinterpret_cast<__m256i*>(raysLow), childRays);
      if constexpr (kWide) _mm256_store_si256(reinterpret_cast<__m256i*>(raysHigh), childRaysHigh);
      _mm256_store_ps(nearOf, childNear);
      // Closest-hit packets visit the nearest child first. Any-hit packets take
      // the children unsorted, the last lane first, as Embree's packets do:
      // measured faster than nearest first for shadow and AO packets on all five
      // built-in scenes, and on the same scenes mirrored through the origin (so
      // that the lane order's spatial bias points the other way): Robots'
      // shadow rays 14.6 -> 7.0 ms (mirrored 14.6 -> 11.0), AO 87.5 -> 72.7 ms
      // (86.0 -> 82.0); the others 1-18 % (docs/bench-speed/NOTES.md).
      Entry hits[8];
      int n = 0;
      for (int lane = 0; lane < kWideBvhWidth; ++lane) {
        Mask raysOf = raysLow[lane];
        if (anyAcross) raysOf |= acrossRays[lane];
        if constexpr (kWide) raysOf |= Mask(raysHigh[lane]) << 32;
        if (!raysOf) continue;
        Entry e{node.child[lane], nearOf[lane], raysOf};
        if constexpr (kAnyHit) {
          stack[top++] = e;
          continue;
        }
        int j = n++;
        while (j > 0 && hits[j - 1].tNear > e.tNear) {
          hits[j] = hits[j - 1];
          --j;
        }
        hits[j] = e;
      }
      for (int i = n; i-- > 0;) stack[top++] = hits[i];
      return;
    }
    const uint32_t first = wideLeafFirst(entry.ref), packs = wideLeafPacks(entry.ref);
    uint32_t real[4];  // each pack's real triangles (wideLeafPacks <= 4), counted once for all the rays
    for (uint32_t p = 0; p < packs; ++p) {
      real[p] = 0;
      for (uint32_t id : bvh.packs[first + p].id) real[p] += id != kNoHit;
    }
    // Groups of eight rays with enough of them here test the leaf one triangle
    // against eight rays; the others, each ray against a pack at a time.
    Mask perRay = 0;
    for (Mask left = live; left;) {
      const int g = __builtin_ctzll(left) >> 3;
      const Mask group = left & (Mask(0xFF) << (8 * g));
      left &= ~group;
      if (__builtin_popcountll(group) < config.acrossRaysAt) {
        perRay |= group;
        continue;
      }
      const uint32_t found = leafAcrossRays<kAnyHit>(bvh, first, packs, real, rays, g,
                                                     uint32_t(uint64_t(group) >> (8 * g)), tBest, best, tests);
      alive &= ~(Mask(found) << (8 * g));
    }
    for (Mask m = perRay; m;) {
      const int r = __builtin_ctzll(m);
      m &= m - 1;
      for (uint32_t p = first; p < first + packs; ++p) {
        const TrianglePack& pack = bvh.packs[p];
        float t[4], u[4], v[4];
        uint32_t hit = packTest4(pack, pre[r], tBest[r], t, u, v);
        tests[r] += real[p - first];
        while (hit) {
          const int lane = __builtin_ctz(hit);
          hit &= hit - 1;
          if (t[lane] < tBest[r]) best[r] = Hit{t[lane], u[lane], v[lane], pack.id[lane]}, tBest[r] = t[lane];
        }
        if (kAnyHit && best[r].found()) {
          alive &= ~(Mask(1) << r);
          break;
        }
      }
    }
    if (!alive) top = 0;  // every ray has stopped
  }

private:
  WIDE_TARGET void stepSingles() {
    SingleWalk& w = single_[turn_];
    const int r = w.ray;
    if (singleStep<kAnyHit>(*bvh_, pre_[r], best_[r], steps_[r], tests_[r], w)) {
      prefetchVisit(*bvh_, w.entry.ref);
      turn_ = turn_ + 1 < singles_ ? turn_ + 1 : 0;
      return;
    }
    tBest_[r] = best_[r].t;
    if (kAnyHit && best_[r].found()) alive_ &= ~(Mask(1) << r);
    w = single_[--singles_];  // the last walk moves here with its stack (none starts before all end)
    if (turn_ >= singles_) turn_ = 0;
    if (singles_ == 0 && !alive_) top_ = 0;  // every ray has stopped
  }


  const WideBvh* bvh_ = nullptr;
  const RayPacket* rays_ = nullptr;
  const PacketConfig* config_ = nullptr;
  Hit* best_ = nullptr;
  RayStats* stats_ = nullptr;
  RayPre pre_[kWidePacketMax];
  alignas(32) uint32_t steps_[kWidePacketMax];
  alignas(32) uint32_t tests_[kWidePacketMax];
  // best[r].t kept dense as well: which rays an entry still matters to is then
  // one vector compare per eight rays instead of a loop over the rays.
  alignas(32) float tBest_[kWidePacketMax];
  alignas(32) float inv_[3][kWidePacketMax];
  Mask acrossCandidates_ = 0, alive_ = 0;
  Entry local_[256];
  std::vector<Entry> heap_;
  Entry* stack_ = local_;
  int top_ = 0;
  // Rays walking a subtree alone (PacketConfig::singleRayAt), each with its stack.
  SingleWalk single_[kWidePacketMax];
  std::vector<StackEntry> singleStacks_;
  int singles_ = 0, turn_ = 0;
};

// Packets take turns a visit at a time, kPacketsInFlight of them at once:
// after a packet's visit the lines of its next one are prefetched, and they
// arrive while the other packets visit theirs. A walk that is done hands its
// slot to the next packet. At 5 M triangles a packet alone waits on its
// misses one at a time (the tree is 0.8 GB; a miss costs about what a visit
// does); four in turn keep the core's miss buffers full: the prefetch itself
// is where they then stall (perf), so more in flight do not help. Frame time
// at 5 M spheres (-b 1, 512², Embree -r 3 over ours, median of three rounds):
// 2 in flight 1.09, 4 1.16, 8 1.08 (docs/bench-speed/NOTES.md).
constexpr int kPacketsInFlight = 4;
template <typename Mask, bool kAnyHit>
WIDE_TARGET void tracePackets(const WideBvh& bvh, std::span<const PacketJob> jobs, const PacketConfig& config,
                              bool takeTurns) {
  if (!takeTurns) {  // one packet after another, each to its end
    PacketWalk<Mask, kAnyHit, false> walk;
    for (const PacketJob& job : jobs) {
      walk.start(bvh, job, config);
      while (!walk.done()) walk.step();
      walk.finish();
    }
    return;
  }
  PacketWalk<Mask, kAnyHit, true> walks[kPacketsInFlight];
  int slot[kPacketsInFlight], busy = 0;  // the walks under way
  size_t nextJob = 0;
  for (; busy < kPacketsInFlight && nextJob < jobs.size(); ++busy) {
    slot[busy] = busy;
    walks[busy].start(bvh, jobs[nextJob++], config);
  }
  while (busy > 0) {
    for (int i = 0; i < busy;) {
      PacketWalk<Mask, kAnyHit, true>& walk = walks[slot[i]];
      if (!walk.done()) walk.step();
      if (!walk.done()) {
        prefetchVisit(bvh, walk.next());
        ++i;
        continue;
      }
      walk.finish();
      if (nextJob < jobs.size()) {
        walk.start(bvh, jobs[nextJob++], config);
        ++i;
      } else {
        slot[i] = slot[--busy];
      }
    }
  }
}

}  // namespace

Hit traverseWideBvhAvx2(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                        TriangleTest test, RayStats* stats) {
  return traverse(bvh, tris, ray, anyHit, test, stats);
}

void traceWideBvhPacketsAvx2(const WideBvh& bvh, std::span<const PacketJob> jobs, bool anyHit,
                             const PacketConfig& config, bool takeTurns) {
  const bool wide = std::any_of(jobs.begin(), jobs.end(), [](const PacketJob& job) { return job.rays->count > 32; });
  if (wide)
    (anyHit ? tracePackets<uint64_t, true> : tracePackets<uint64_t, false>)(bvh, jobs, config, takeTurns);
  else
    (anyHit ? tracePackets<uint32_t, true> : tracePackets<uint32_t, false>)(bvh, jobs, config, takeTurns);
}

void traceWideBvhPacketAvx2(const WideBvh& bvh, const RayPacket& rays, bool anyHit, std::span<Hit> hits,
                            std::span<RayStats> stats, const PacketConfig& config) {
  const PacketJob job{&rays, hits.data(), stats.data()};
  traceWideBvhPacketsAvx2(bvh, std::span<const PacketJob>(&job, 1), anyHit, config, false);
}

bool wideBvhAvx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

}  // namespace passtrace

#else  // not x86: no AVX2 build; the scalar traversal serves every call

namespace passtrace {

Hit traverseWideBvhAvx2(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                        TriangleTest test, RayStats* stats) {
  return traverseWideBvhScalar(bvh, tris, ray, anyHit, test, stats);
}

void traceWideBvhPacketAvx2(const WideBvh&, const RayPacket&, bool, std::span<Hit>, std::span<RayStats>,
                            const PacketConfig&) {}
void traceWideBvhPacketsAvx2(const WideBvh&, std::span<const PacketJob>, bool, const PacketConfig&, bool) {}

bool wideBvhAvx2Available() { return false; }

}  // namespace passtrace
#endif
