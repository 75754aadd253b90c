#include "render/stream_ray_query.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "accel/ray_stream_layout.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"

namespace passtrace {

StreamRayQuery::StreamRayQuery(GpuTraversal& traversal)
    : traversal_(traversal), cull_(std::make_unique<StreamKernel>("cull", "cull.frag", StreamKernel::Depth::Cull)) {}

StreamRayQuery::~StreamRayQuery() = default;

uint64_t StreamRayQuery::trace(std::span<const Ray> rays, std::span<const uint8_t> anyHit, std::span<Hit> hits,
                               std::span<RayStats> stats, std::span<glm::vec4> finalStates) {
  if (hits.size() != rays.size() || (!stats.empty() && stats.size() != rays.size()) ||
      (!finalStates.empty() && finalStates.size() != rays.size()) ||
      (!anyHit.empty() && anyHit.size() != rays.size()))
    throw std::invalid_argument("StreamRayQuery::trace: anyHit, hits and stats need one entry per ray");
  uint64_t passes = 0;
  const size_t perStream = size_t(kStreamWidth) * kMaxStreamHeight;
  for (size_t first = 0; first < rays.size(); first += perStream) {
    const size_t count = std::min(perStream, rays.size() - first);
    const int height = int((count + kStreamWidth - 1) / kStreamWidth);
    InOutStream stream(kStreamWidth, height, kRaySurfaceCount);
    // Elements past `count` are finished from the start (state.w = 0).
    const size_t n = stream.elementCount();
    std::vector<glm::vec4> origin(n, glm::vec4(0.0f)), direction(n, glm::vec4(0, 0, 1, kInfinity)),
        state(n, glm::vec4(packIndex(0), 0, 0, 0)), hit(n, glm::vec4(kInfinity, 0, 0, packIndex(0)));
    for (size_t i = 0; i < count; ++i) {
      const Ray& r = rays[first + i];
      const bool shadow = !anyHit.empty() && anyHit[first + i];
      origin[i] = glm::vec4(r.origin, float(shadow ? RayKind::Shadow : RayKind::Nearest));
      direction[i] = glm::vec4(r.direction, r.tMax);
      state[i].w = 1.0f;
      hit[i].x = r.tMax;
    }
    stream.upload(kOriginSurface, origin);
    stream.upload(kDirectionSurface, direction);
    stream.upload(kStateSurface, state);
    stream.upload(kHitSurface, hit);
    cull_->bindInput("uState", stream, kStateSurface);
    stream.enable();
    stream.clearDepth(1.0f);
    const uint64_t active = n - cull_->execute(true);
    passes += traversal_.trace(stream, active, [&] { return cull_->execute(true); });
    stream.disable();

    const std::vector<glm::vec4> found = stream.read(kHitSurface);
    for (size_t i = 0; i < count; ++i) {
      const glm::vec4& h = found[i];
      const float tMax = rays[first + i].tMax;
      hits[first + i] = h.x < tMax ? Hit{h.x, h.y, h.z, unpackIndex(h.w)} : Hit{};
    }
    if (!stats.empty() || !finalStates.empty()) {
      // Every traversal kernel counts in the state surface (y steps, z
      // triangle tests), which the shade pass adds to the heat map's sums.
      const std::vector<glm::vec4> state = stream.read(kStateSurface);
      for (size_t i = 0; i < count && !stats.empty(); ++i)
        stats[first + i] = RayStats{uint32_t(state[i].y), uint32_t(state[i].z)};
      if (!finalStates.empty()) std::copy_n(state.begin(), count, finalStates.begin() + first);
    }
  }
  return passes;
}

}  // namespace passtrace
