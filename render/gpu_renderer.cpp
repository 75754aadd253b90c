#include "render/gpu_renderer.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <limits>

#include "render/camera.h"
#include "accel/ray_stream_layout.h"
#include "render/scene_streams.h"
#include "render/shading.h"
#include "stream/active_elements.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

const std::vector<int> kAllSurfaces = {kOriginSurface,  kDirectionSurface,  kStateSurface,  kHitSurface,
                                       kColorSurface,   kThroughputSurface, kPendingSurface};
// The last bounce's shading: what render() reads afterwards, the colour and
// the counters (throughput's and pending's w). The rest is not stored, which
// in the compute stage saves an image store per element and surface.
constexpr int kNone = InOutStream::kNoSurface;
const std::vector<int> kFinalSurfaces = {kNone, kNone, kNone, kNone, kColorSurface, kThroughputSurface, kPendingSurface};

using Clock = std::chrono::steady_clock;

}  // namespace

void setRaygenCamera(StreamKernel& raygen, const CameraBasis& basis) {
  raygen.set("uEye", basis.eye);
  raygen.set("uForward", basis.forward);
  raygen.set("uRight", basis.right);
  raygen.set("uUp", basis.up);
  raygen.set("uTanHalfFov", basis.tanHalfFov);
  raygen.set("uResolution", glm::vec2(basis.width, basis.height));
  setRowBands(raygen, basis.rows);
}

void setRowBands(StreamKernel& kernel, const RowBands& rows) {
  kernel.set("uRowBands", glm::ivec3(rows.bandHeight, rows.ranks, rows.rank));
}

GpuRenderer::GpuRenderer(const Scene& scene, GpuTraversal& traversal, int width, int height, uint64_t maxPageTexels,
                         ShadingConfig shading, Compaction compact)
    : scene_(scene),
      traversal_(traversal),
      rays_(width, height, kRaySurfaceCount),
      maxPageTexels_(maxPageTexels),
      triangles_(triangleShadingStream(scene, maxPageTexels)),
      materials_(materialTexels(scene), "materials", maxPageTexels),
      raygen_("raygen", "raygen.frag"),
      cull_("cull", "cull.frag", StreamKernel::Depth::Cull),
      shade_("shade", "shade.frag", StreamKernel::Depth::Test,
             {streamPagesDefine({triangles_.get(), &materials_}), shadingTexelsDefine(scene)}),
      shading_(shading),
      compact_(compact) {
  cull_.bindInput("uState", rays_, kStateSurface);
  const char* samplers[] = {"uOrigin", "uDirection", "uState", "uHit", "uColor", "uThroughput", "uPending"};
  for (int s : kAllSurfaces) shade_.bindInput(samplers[s], rays_, s);
  if (shading.mode != ShadingMode::Thesis) makeMixKernel();
  if (const FusedBounce* fused = traversal.fusedBounce(); fused && shading.mode == ShadingMode::Thesis) {
    std::vector<const ConstInputStream*> streams = fused->streams;
    streams.insert(streams.end(), {triangles_.get(), &materials_});
    std::vector<std::string> defines = fused->defines;
    defines.push_back(streamPagesDefine(streams));
    if (fused->largeStream) defines.push_back(largeStreamPagesDefine(*fused->largeStream));
    defines.push_back(shadingTexelsDefine(scene));
    fused_ = std::make_unique<StreamKernel>("fused bounce", fused->glslFile, StreamKernel::Depth::Test, defines);
    traversal.bindFused(*fused_);
    unfinished_ = std::make_unique<StorageBuffer>("the fused bounce's count of unfinished rays");
    unfinished_->reserve(1);
    fused_->bindStorage(0, *unfinished_);
  }
  bindThesisShading();
  if (compact != Compaction::Off) compaction_ = std::make_unique<StreamCompaction>(rays_, kStateSurface);
}

double GpuRenderer::extraBytesPerPixel(const ShadingConfig& shading, Compaction compact, StreamStage stage) {
  double bytes = 0;
  if (shading.mode == ShadingMode::Whitted) bytes += sizeof(float) * kWhittedStackFloats * kWhittedStackSize;
  if (compact != Compaction::Off) bytes += StreamCompaction::bytesPerElement(kRaySurfaceCount);
  if (stage == StreamStage::Compute)  // the rays' stream, and the compaction's when there is one
    bytes += ActiveElements::bytesPerElement() * (compact != Compaction::Off ? 2 : 1);
  return bytes;
}

void GpuRenderer::makeMixKernel() {
  const char* samplers[] = {"uOrigin", "uDirection", "uState", "uHit", "uColor", "uThroughput", "uPending"};
  if (shading_.mode == ShadingMode::Whitted) {
    whittedMaterials_ =
        std::make_unique<ConstInputStream>(whittedMaterialTexels(scene_), "whitted materials", maxPageTexels_);
    whittedStacks_ = std::make_unique<StorageBuffer>("whitted ray stacks");
    whittedStacks_->reserve(uint64_t(rays_.elementCount()) * kWhittedStackFloats * uint64_t(kWhittedStackSize));
    mixShade_ = std::make_unique<StreamKernel>(
        "shade_whitted", "shade_whitted.frag", StreamKernel::Depth::Test,
        std::vector<std::string>{streamPagesDefine({triangles_.get(), whittedMaterials_.get()}), shadingTexelsDefine(scene_),
                                 "STACK_SIZE " + std::to_string(kWhittedStackSize),
                                 "MAX_LIGHTS " + std::to_string(kWhittedMaxLights)});
    mixShade_->bindInput("uMaterials", *whittedMaterials_);
    mixShade_->bindStorage(1, *whittedStacks_);
    mixShade_->set("uMinThroughput", kWhittedMinThroughput);
  } else {
    mixShade_ = std::make_unique<StreamKernel>("shade_ao", "shade_ao.frag", StreamKernel::Depth::Test,
                                               std::vector<std::string>{streamPagesDefine({triangles_.get()}),
                                                                        shadingTexelsDefine(scene_)});
    mixShade_->set("uSamples", shading_.aoSamples);
    mixShade_->set("uAoDistance", aoDistance(scene_, shading_));
  }
  for (int s : kAllSurfaces) mixShade_->bindInput(samplers[s], rays_, s);
  mixShade_->set("uStreamWidth", uint32_t(rays_.width()));
  mixLightChanged();
}

// The uniforms that follow the scene (trianglesMoved too).
void GpuRenderer::mixLightChanged() {
  if (!mixShade_) return;
  mixShade_->bindInput("uTriangles", *triangles_);
  mixShade_->set("uBackground", scene_.background);
  mixShade_->set("uEpsilon", secondaryRayEpsilon(scene_));
  if (shading_.mode == ShadingMode::Whitted) {
    const int lights = whittedLightCount(scene_);
    for (int k = 0; k < lights; ++k) {
      // Appended, not "[" + ...: GCC 12 warns (-Wrestrict) on that insert once inlined here.
      const auto element = [k](std::string array) { return (array += '[') += std::to_string(k) + ']'; };
      mixShade_->set(element("uLightPositions").c_str(), whittedLight(scene_, k).position);
      mixShade_->set(element("uLightColors").c_str(), whittedLight(scene_, k).color);
    }
    mixShade_->set("uLightCount", lights);
    mixShade_->set("uAmbient", scene_.ambient);
  } else {
    mixShade_->set("uAoDistance", aoDistance(scene_, shading_));
  }
}

// The inputs of shade_thesis.glsl, in shade.frag and in a fused bounce.
void GpuRenderer::bindThesisShading() {
  const float epsilon = secondaryRayEpsilon(scene_);  // a pass over the triangles: once for both kernels
  for (StreamKernel* kernel : {&shade_, fused_.get()}) {
    if (!kernel) continue;
    kernel->bindInput("uTriangles", *triangles_);
    kernel->bindInput("uMaterials", materials_);
    kernel->set("uLightPosition", scene_.light.position);
    kernel->set("uLightColor", scene_.light.color);
    kernel->set("uBackground", scene_.background);
    kernel->set("uAmbient", scene_.ambient);
    kernel->set("uEpsilon", epsilon);  // it follows the scene's bounds
  }
}

void GpuRenderer::trianglesMoved() {
  // Same size, same pages: the shading kernel's STREAM_PAGES still holds.
  // An animated light follows too.
  triangles_ = triangleShadingStream(scene_, maxPageTexels_);
  bindThesisShading();
  mixLightChanged();
}

uint64_t GpuRenderer::retireFinished() { return cull_.execute(true); }

void GpuRenderer::readPrimaryHits(FrameResult& result) const {
  result.primaryHits.reserve(rays_.elementCount());
  for (const glm::vec4& h : rays_.read(kHitSurface))
    result.primaryHits.push_back(h.x < kInfinity ? HitRecord{h.x, h.y, h.z, unpackIndex(h.w)}
                                                 : HitRecord{kInfinity, 0.0f, 0.0f, kNoHit});
}

bool GpuRenderer::fusedPrimaryBounce(const CameraBasis& basis, int bounces, bool captureHits, FrameResult& result,
                                     Clock::duration& excluded) {
  // --hits reads the primary hits, which a later bounce's shading overwrites;
  // --compact always asks for the bounce's rays gathered.
  if (!fused_ || (captureHits && bounces > 1) || compact_ == Compaction::Always) return false;
  setRaygenCamera(*fused_, basis);
  fused_->set("uLastBounce", bounces == 1 ? 1 : 0);
  fused_->set("uKeepHit", captureHits ? 1 : 0);
  unfinished_->zero(1);
  rays_.clearDepth(1.0f);
  // After the last bounce only the colour and the counters are read (and the
  // primary hits for --hits): the other surfaces are not written.
  std::vector<int> writes = bounces > 1 ? kAllSurfaces : kFinalSurfaces;
  if (captureHits) writes[kHitSurface] = kHitSurface;
  rays_.setWriteSurfaces(writes);
  fused_->execute();
  // A ray that needs more steps than one pass may run (the loop budget):
  // the whole bounce runs again pass by pass, which is exact.
  if (std::bit_cast<uint32_t>(unfinished_->read(1).at(0)) != 0) return false;
  result.stats.rays += rays_.elementCount();
  result.stats.passes += 1;
  if (captureHits) {
    glFinish();
    const auto pause = Clock::now();
    readPrimaryHits(result);
    excluded += Clock::now() - pause;
  }
  return true;
}

FrameResult GpuRenderer::render(const CameraSpec& camera, int bounces, bool captureHits, const RowBands& rows) {
  const CameraBasis basis = makeCameraBasis(camera, rays_.width(), rays_.height(), rows);
  FrameResult result;
  result.width = rays_.width();
  result.height = rays_.height();
  const uint64_t elements = rays_.elementCount();

  rays_.enable();
  glFinish();  // start the clock on an idle pipeline
  Clock::duration excluded{};
  const auto start = Clock::now();

  int first = 1;  // the first bounce traced pass by pass
  lastFrameFused_ = fusedPrimaryBounce(basis, bounces, captureHits, result, excluded);
  if (lastFrameFused_) {
    first = 2;
  } else {
    setRaygenCamera(raygen_, basis);
    rays_.clearDepth(1.0f);
    rays_.setWriteSurfaces(kAllSurfaces);
    raygen_.execute();
  }

  // Whitted and AO trace until no element has a ray left (see CpuRenderer).
  const bool thesis = shading_.mode == ShadingMode::Thesis;
  const int generations = thesis ? bounces : std::numeric_limits<int>::max();
  if (shading_.mode == ShadingMode::Whitted) mixShade_->set("uMaxDepth", bounces);
  if (mixShade_) setRowBands(*mixShade_, rows);  // AO's samples follow the whole image's pixel
  for (int bounce = first; bounce <= generations; ++bounce) {
    rays_.clearDepth(1.0f);
    const uint64_t active = elements - retireFinished();
    if (active == 0) break;
    result.stats.rays += active;
    const bool sparse = double(active) <= kCompactLiveFraction * double(elements);
    if (compact_ == Compaction::Always || (compact_ == Compaction::On && sparse)) {
      // The traversal runs on the compact stream; rays_'s depth keeps marking
      // the live rays until scatter() has copied their results back.
      compaction_->gather(active);
      result.stats.passes += traversal_.trace(compaction_->compact(), active, [this] { return compaction_->retire(); });
      compaction_->scatter();
    } else {
      result.stats.passes += traversal_.trace(rays_, active, [this] { return retireFinished(); });
    }

    if (bounce == 1 && captureHits) {
      glFinish();
      const auto pause = Clock::now();
      readPrimaryHits(result);
      excluded += Clock::now() - pause;
    }

    rays_.clearDepth(1.0f);
    // After the thesis's last bounce only the colour and the counters are read
    // (the primary hits were read above), as after the fused bounce.
    rays_.setWriteSurfaces(thesis && bounce == bounces ? kFinalSurfaces : kAllSurfaces);
    if (thesis) {
      shade_.set("uLastBounce", bounce == bounces ? 1 : 0);
      shade_.execute();
    } else {
      mixShade_->execute();
    }
  }
  glFinish();
  result.stats.frameMs = std::chrono::duration<double, std::milli>(Clock::now() - start - excluded).count();

  const std::vector<glm::vec4> color = rays_.read(kColorSurface);
  result.rgb.reserve(3 * elements);
  for (const glm::vec4& c : color) result.rgb.insert(result.rgb.end(), {c.r, c.g, c.b});
  result.steps.reserve(elements);
  for (const glm::vec4& t : rays_.read(kThroughputSurface)) {
    result.steps.push_back(t.w);
    result.stats.steps += uint64_t(t.w);
    result.stats.maxStepsPerRay = std::max(result.stats.maxStepsPerRay, uint64_t(t.w));
  }
  for (const glm::vec4& p : rays_.read(kPendingSurface)) {
    result.stats.triangleTests += uint64_t(p.w);
    result.stats.maxTriangleTestsPerRay = std::max(result.stats.maxTriangleTestsPerRay, uint64_t(p.w));
  }
  rays_.disable();
  return result;
}

}  // namespace passtrace
