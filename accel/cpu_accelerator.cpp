#include "accel/cpu_accelerator.h"

#include "accel/brute_force.h"

namespace passtrace {
namespace {

class BruteForce final : public CpuAccelerator {
public:
  BruteForce(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    stats_.name = "brute-force";
    stats_.references = tris.size();
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return intersectBruteForce(tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  AccelStats stats_;
  TriangleTest test_;
};

}  // namespace

std::optional<FilterStats> CpuAccelerator::traceBatch(const RayBatch& batch, std::span<Hit> hits,
                                                      std::span<RayStats> stats) const {
  for (size_t i = 0; i < batch.rays.size(); ++i)
    if (batch.active[i]) hits[i] = intersect(batch.rays[i], batch.anyHit[i] != 0, &stats[i]);
  return std::nullopt;
}

std::unique_ptr<CpuAccelerator> makeBruteForceAccelerator(std::span<const Triangle> tris, TriangleTest test) {
  return std::make_unique<BruteForce>(tris, test);
}

}  // namespace passtrace
