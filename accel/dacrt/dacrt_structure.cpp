#include "accel/dacrt/dacrt_structure.h"

#include <stdexcept>
#include <string>

#include "accel/dacrt/dacrt_tracer.h"

namespace passtrace {
namespace {

class Dacrt final : public CpuAccelerator {
public:
  Dacrt(std::span<const Triangle> tris, const dacrt::Settings& settings) : tris_(tris), settings_(settings) {
    stats_.name = "dacrt";
  }

  // One ray is a batch of one: at or under rLimit, so every triangle is
  // tested (tests call this; the renderer calls traceBatch).
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    const uint8_t yes = 1, flag = anyHit ? 1 : 0;
    RayBatch batch;
    batch.rays = std::span(&ray, 1);
    batch.active = std::span(&yes, 1);
    batch.anyHit = std::span(&flag, 1);
    batch.threads = 1;
    Hit hit;
    RayStats local;
    dacrt::trace(tris_, settings_, batch, std::span(&hit, 1), std::span(&local, 1));
    if (stats) stats->steps += local.steps, stats->triangleTests += local.triangleTests;
    return hit;
  }

  bool tracesBatches() const override { return true; }
  std::optional<FilterStats> traceBatch(const RayBatch& batch, std::span<Hit> hits,
                                        std::span<RayStats> stats) const override {
    return dacrt::trace(tris_, settings_, batch, hits, stats);
  }

  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  dacrt::Settings settings_;
  AccelStats stats_;  // all zero: nothing is built or stored
};

}  // namespace

std::unique_ptr<CpuAccelerator> makeDacrtCpu(std::span<const Triangle> tris, const AccelBuildConfig& config) {
  if (config.dacrtRLimit < 1) throw std::invalid_argument("--dacrt-rlimit must be at least 1");
  if (config.dacrtPLimit < 1) throw std::invalid_argument("--dacrt-plimit must be at least 1");
  dacrt::Settings settings;
  settings.rLimit = config.dacrtRLimit;
  settings.pLimit = config.dacrtPLimit;
  settings.cones = config.dacrtCones;
  settings.medianSplit = config.dacrtMedianSplit;
  settings.test = config.triangleTest;
  return std::make_unique<Dacrt>(tris, settings);
}

}  // namespace passtrace
