#include "accel/bvh_fast/bvh2_traversal.h"

#include <limits>

namespace passtrace {

void stepBvh2(const Bvh2Texels& texels, const Ray& ray, const glm::vec3& invDir, bool anyHit, Bvh2Cursor& c,
              TriangleTest test) {
  ++c.stats.steps;
  const glm::vec4* t = &texels.nodes[4 * size_t(c.node)];
  bool enter[2] = {false, false};
  float entry[2] = {0.0f, 0.0f};
  uint32_t child[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const glm::vec4 lo = t[2 * k], hi = t[2 * k + 1];
    if (hi.w == kBvh2Triangle) {
      ++c.stats.triangleTests;
      const uint32_t id = unpackBvh2Index(lo.w);
      const glm::vec4* v = &texels.triangles[3 * size_t(id)];
      const Triangle tri{glm::vec3(v[0]), glm::vec3(v[1]), glm::vec3(v[2])};
      if (intersectTriangle(ray.origin, ray.direction, tri, id, c.best, test) && anyHit) {
        c.done = true;
        return;
      }
    } else if (hi.w == kBvh2Node) {
      float tNear, tFar;
      clipToBox(ray.origin, invDir, Aabb{glm::vec3(lo), glm::vec3(hi)}, tNear, tFar);
      const float tExit = tFar * kRobustExitScale;
      enter[k] = tNear <= tExit && tExit >= 0.0f && tNear < c.best.t;
      entry[k] = tNear;
      child[k] = unpackBvh2Index(lo.w);
    }
  }
  if (enter[0] && enter[1]) {
    const int nearK = entry[1] < entry[0] ? 1 : 0;
    c.stack.emplace_back(child[1 - nearK], entry[1 - nearK]);
    c.node = child[nearK];
    return;
  }
  if (enter[0] || enter[1]) {
    c.node = enter[0] ? child[0] : child[1];
    return;
  }
  while (!c.stack.empty()) {
    const auto [node, tEntry] = c.stack.back();
    c.stack.pop_back();
    if (tEntry < c.best.t) {
      c.node = node;
      return;
    }
  }
  c.done = true;
}

namespace {

class Bvh2Mirror final : public CpuAccelerator {
 public:
  Bvh2Mirror(Bvh2Texels texels, AccelStats stats, TriangleTest test)
      : texels_(std::move(texels)), stats_(std::move(stats)), test_(test) {}

  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    Bvh2Cursor c;
    c.best.t = ray.tMax;
    c.stack.reserve(texels_.depth);
    if (texels_.nodes.empty()) return c.best;
    const glm::vec3 invDir = safeInverse(ray.direction);
    while (!c.done) stepBvh2(texels_, ray, invDir, anyHit, c, test_);
    if (stats) {
      stats->steps += c.stats.steps;
      stats->triangleTests += c.stats.triangleTests;
    }
    return c.best;
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

 private:
  Bvh2Texels texels_;
  AccelStats stats_;
  TriangleTest test_;
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeBvh2Mirror(Bvh2Texels texels, AccelStats stats, TriangleTest test) {
  return std::make_unique<Bvh2Mirror>(std::move(texels), std::move(stats), test);
}

}  // namespace passtrace
