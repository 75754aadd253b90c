#include "accel/milliseconds_since.h"
#include "render/dynamic_renderer.h"

#include <chrono>
#include <optional>
#include <stdexcept>

#include "accel/kd/gpu_kd_dynamic.h"
#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"

namespace passtrace {
namespace {

using Clock = std::chrono::steady_clock;

class DynamicCpu final : public DynamicRenderer {
 public:
  DynamicCpu(DynamicStrategy strategy, const Structure& structure, const Scene& scene, const RendererConfig& config)
      : scene_(scene), config_(config), name_(structure.name), variant_(kdDynamicVariant(structure.name)),
        trees_(strategy, scene.triangles, scene.moving, config.gpu.build) {}
  double staticBuildMs() const override { return trees_.staticBuildMs(); }
  double nextFrame() override {
    renderer_.reset();
    accelerator_.reset();
    const auto start = Clock::now();
    trees_.update(scene_.triangles);
    accelerator_ = makeKdDynamicCpu(trees_, variant_, scene_.triangles, config_.gpu.build.triangleTest, name_, 0.0);
    frameMs_ = millisecondsSince(start);
    renderer_ = std::make_unique<CpuRenderer>(scene_, *accelerator_, config_.threads, config_.shading);
    return frameMs_;
  }
  FrameResult render(const CameraSpec& camera, bool captureHits) override {
    if (!renderer_) throw std::logic_error("DynamicRenderer: nextFrame() before render()");
    return renderer_->render(camera, config_.width, config_.height, config_.bounces, captureHits, config_.rows);
  }
  AccelStats structureStats() const override {
    AccelStats s = accelerator_ ? accelerator_->stats() : AccelStats{.name = name_};
    s.buildMs = frameMs_;
    return s;
  }

 private:
  const Scene& scene_;
  RendererConfig config_;
  std::string name_;
  std::optional<KdStreamVariant> variant_;
  KdDynamicTrees trees_;
  std::unique_ptr<CpuAccelerator> accelerator_;
  std::unique_ptr<CpuRenderer> renderer_;
  double frameMs_ = 0;
};

KdStreamVariant streamVariant(const Structure& structure) {
  const std::optional<KdStreamVariant> variant = kdDynamicVariant(structure.name);
  if (!variant) throw std::invalid_argument(std::string(structure.name) + " has no GPU stream traversal");
  return *variant;
}

class DynamicStream final : public DynamicRenderer {
 public:
  DynamicStream(DynamicStrategy strategy, const Structure& structure, const Scene& scene, const RendererConfig& config)
      : scene_(scene), config_(config), name_(structure.name), variant_(streamVariant(structure)),
        trees_(strategy, scene.triangles, scene.moving, config.gpu.build) {}
  double staticBuildMs() const override { return trees_.staticBuildMs(); }
  double nextFrame() override {
    double ms = trees_.update(scene_.triangles);
    if (!traversal_) {
      // The first frame makes the kernels (compiled on its first draw); only
      // its flattening counts, as in the frames after it.
      traversal_ = std::make_unique<GpuKdDynamicTraversal>(trees_, variant_, scene_.triangles,
                                                           withPassStepLimit(config_.gpu));
      ms += traversal_->firstFlattenMs();
      renderer_ = std::make_unique<GpuRenderer>(scene_, *traversal_, config_.width, config_.height,
                                                config_.gpu.maxPageTexels, config_.shading, config_.gpu.compact);
    } else {
      ms += traversal_->update(scene_.triangles);
      renderer_->trianglesMoved();
    }
    frameMs_ = ms;
    return ms;
  }
  FrameResult render(const CameraSpec& camera, bool captureHits) override {
    if (!renderer_) throw std::logic_error("DynamicRenderer: nextFrame() before render()");
    return renderer_->render(camera, config_.bounces, captureHits, config_.rows);
  }
  AccelStats structureStats() const override {
    AccelStats s = traversal_ ? traversal_->stats() : AccelStats{.name = name_};
    s.name = name_;
    s.buildMs = frameMs_;
    return s;
  }

 private:
  const Scene& scene_;
  RendererConfig config_;
  std::string name_;
  KdStreamVariant variant_;
  KdDynamicTrees trees_;
  std::unique_ptr<GpuKdDynamicTraversal> traversal_;
  std::unique_ptr<GpuRenderer> renderer_;
  double frameMs_ = 0;
};

}  // namespace

std::unique_ptr<DynamicRenderer> makeDynamicRenderer(DynamicStrategy strategy, RendererId id, const Structure& structure,
                                                     const Scene& scene, const RendererConfig& config) {
  if (id == RendererId::Gpu) return std::make_unique<DynamicStream>(strategy, structure, scene, config);
  if (id == RendererId::Cpu) return std::make_unique<DynamicCpu>(strategy, structure, scene, config);
  throw std::invalid_argument("--dynamic: the " + std::string(rendererTitle(id)) + " renderer has no dynamic strategies");
}

}  // namespace passtrace
