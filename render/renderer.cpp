#include "render/renderer.h"

#include <stdexcept>

#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"
#include "render/preview_renderer.h"

namespace passtrace {
namespace {

class PreviewRenderer final : public Renderer {
 public:
  PreviewRenderer(const Scene& scene, const RendererConfig& config) : scene_(scene), config_(config) {}
  FrameResult render(const CameraSpec& camera, bool) override {
    return renderPreview(scene_, camera, config_.width, config_.height);
  }
  AccelStats structureStats() const override { return AccelStats{.name = "none"}; }

 private:
  const Scene& scene_;
  RendererConfig config_;
};

// -r 1 and -r 3: the CPU ray tracer over a CpuAccelerator.
class CpuTracer final : public Renderer {
 public:
  CpuTracer(std::unique_ptr<CpuAccelerator> structure, const Scene& scene, const RendererConfig& config)
      : structure_(std::move(structure)), renderer_(scene, *structure_, config.threads, config.shading), config_(config) {}
  FrameResult render(const CameraSpec& camera, bool captureHits) override {
    return renderer_.render(camera, config_.width, config_.height, config_.bounces, captureHits, config_.rows);
  }
  AccelStats structureStats() const override { return structure_->stats(); }

 private:
  std::unique_ptr<CpuAccelerator> structure_;
  CpuRenderer renderer_;
  RendererConfig config_;
};

class StreamTracer final : public Renderer {
 public:
  StreamTracer(std::unique_ptr<GpuTraversal> structure, const Scene& scene, const RendererConfig& config)
      : structure_(std::move(structure)),
        renderer_(scene, *structure_, config.width, config.height, config.gpu.maxPageTexels, config.shading,
                  config.gpu.compact),
        config_(config) {}
  FrameResult render(const CameraSpec& camera, bool captureHits) override {
    return renderer_.render(camera, config_.bounces, captureHits, config_.rows);
  }
  AccelStats structureStats() const override { return structure_->stats(); }

 private:
  std::unique_ptr<GpuTraversal> structure_;
  GpuRenderer renderer_;
  RendererConfig config_;
};

}  // namespace

std::unique_ptr<Renderer> makeRenderer(RendererId id, const Structure* structure, const Scene& scene,
                                       const RendererConfig& config) {
  if (id == RendererId::OpenGl) return std::make_unique<PreviewRenderer>(scene, config);
  if (!structure || !structure->runsOn(id))
    throw std::invalid_argument("the " + std::string(rendererTitle(id)) + " renderer needs a structure it implements");
  if (id == RendererId::Gpu)
    return std::make_unique<StreamTracer>(makeStreamStructure(*structure, scene.triangles, config.gpu), scene, config);
  // Embree runs through the same CPU renderer: same rays, bounces and shading.
  return std::make_unique<CpuTracer>(makeCpuStructure(*structure, scene.triangles, config.gpu.build), scene, config);
}

}  // namespace passtrace
