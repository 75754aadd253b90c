// The wide BVH's traversal in portable scalar code: each lane's operations
// exactly as the AVX2 build performs them (wide_bvh_traversal_avx2.cpp).
#include <cmath>
#include <cstddef>
#include <vector>

#include "accel/wide_bvh/wide_bvh_traversal.h"

namespace passtrace {
namespace {

#define WIDE_TARGET

// glm::min / glm::max / std::max / std::min's comparisons; no NaN reaches them.
inline float lesser(float a, float b) { return b < a ? b : a; }
inline float greater(float a, float b) { return a < b ? b : a; }

struct RayPre;
uint32_t boxTest8(const WideBvhNode& node, const RayPre& pre, float tBest, float* tNear);
uint32_t packTest4(const TrianglePack& pack, const RayPre& pre, float tBest, float* t, float* u, float* v);

#include "accel/wide_bvh/wide_bvh_traverse.inc"

uint32_t boxTest8(const WideBvhNode& node, const RayPre& pre, float tBest, float* tNear) {
  const float* mins[3] = {node.minX, node.minY, node.minZ};
  const float* maxs[3] = {node.maxX, node.maxY, node.maxZ};
  uint32_t mask = 0;
  for (int i = 0; i < kWideBvhWidth; ++i) {
    float s[3], l[3];
    for (int k = 0; k < 3; ++k) {
      const float t0 = (mins[k][i] - pre.o[k]) * pre.inv[k];
      const float t1 = (maxs[k][i] - pre.o[k]) * pre.inv[k];
      s[k] = lesser(t0, t1);
      l[k] = greater(t0, t1);
      if (pre.parallel[k]) {
        const bool inside = pre.o[k] >= mins[k][i] && pre.o[k] <= maxs[k][i];
        s[k] = inside ? -kInfinity : kInfinity;
        l[k] = inside ? kInfinity : -kInfinity;
      }
    }
    const float near = greater(greater(s[0], s[1]), s[2]);
    const float exit = lesser(lesser(l[0], l[1]), l[2]) * kRobustExitScale;
    tNear[i] = near;
    if (near <= exit && exit >= 0.0f && near < tBest) mask |= 1u << i;
  }
  return mask;
}

uint32_t packTest4(const TrianglePack& k, const RayPre& pre, float tBest, float* t, float* u, float* v) {
  uint32_t mask = 0;
  const float dx = pre.d[0], dy = pre.d[1], dz = pre.d[2];
  for (int i = 0; i < kTrianglePackWidth; ++i) {
    const float px = dy * k.e2z[i] - k.e2y[i] * dz;
    const float py = dz * k.e2x[i] - k.e2z[i] * dx;
    const float pz = dx * k.e2y[i] - k.e2x[i] * dy;
    const float det = px * k.e1x[i] + py * k.e1y[i] + pz * k.e1z[i];
    const float invDet = 1.0f / det;
    const float tx = pre.o[0] - k.v0x[i], ty = pre.o[1] - k.v0y[i], tz = pre.o[2] - k.v0z[i];
    u[i] = (px * tx + py * ty + pz * tz) * invDet;
    const float qx = ty * k.e1z[i] - k.e1y[i] * tz;
    const float qy = tz * k.e1x[i] - k.e1z[i] * tx;
    const float qz = tx * k.e1y[i] - k.e1x[i] * ty;
    v[i] = (qx * dx + qy * dy + qz * dz) * invDet;
    t[i] = (qx * k.e2x[i] + qy * k.e2y[i] + qz * k.e2z[i]) * invDet;
    if (det != 0.0f && u[i] >= 0.0f && v[i] >= 0.0f && u[i] + v[i] <= 1.0f && t[i] > 0.0f && t[i] < tBest)
      mask |= 1u << i;
  }
  return mask;
}

}  // namespace

Hit traverseWideBvhScalar(const WideBvh& bvh, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                          TriangleTest test, RayStats* stats) {
  return traverse(bvh, tris, ray, anyHit, test, stats);
}

}  // namespace passtrace
