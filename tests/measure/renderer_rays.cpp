#include "tests/measure/renderer_rays.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "accel/wide_bvh/wide_bvh_traversal.h"
#include "render/ao_sampling.h"
#include "render/camera.h"
#include "render/shading.h"

namespace passtrace {
namespace {

// Pixel indices tile by tile (tileW x tileH, row by row inside a tile).
std::vector<std::vector<size_t>> tiles(int width, int tileW, int tileH) {
  std::vector<std::vector<size_t>> out;
  for (int y0 = 0; y0 < width; y0 += tileH)
    for (int x0 = 0; x0 < width; x0 += tileW) {
      std::vector<size_t>& t = out.emplace_back();
      for (int y = y0; y < std::min(y0 + tileH, width); ++y)
        for (int x = x0; x < std::min(x0 + tileW, width); ++x) t.push_back(size_t(y) * size_t(width) + size_t(x));
    }
  return out;
}

}  // namespace

int parsePositiveInt(const char* name, const char* text) {
  int value = 0;
  const char* end = text + std::strlen(text);
  const auto [at, error] = std::from_chars(text, end, value);
  if (error != std::errc() || at != end || value <= 0)
    throw std::invalid_argument(std::string(name) + ": '" + text + "' is not a positive integer");
  return value;
}

namespace {

void add(PacketSet& set, const std::vector<Ray>& packet) {
  if (packet.empty()) return;
  set.rays += packet.size();
  set.packets.push_back(RayPacket::of(packet));
}

}  // namespace

std::optional<RayToolArgs> parseRayToolArgs(int argc, char** argv, int defaultRepeats) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE|spheres:N [WIDTH=512] [REPEATS=%d] [AO_SAMPLES=4]\n", argv[0], defaultRepeats);
    return std::nullopt;
  }
  RayToolArgs args{argv[1]};
  args.repeats = defaultRepeats;
  if (argc > 2) args.width = parsePositiveInt("WIDTH", argv[2]);
  if (argc > 3) args.repeats = parsePositiveInt("REPEATS", argv[3]);
  if (argc > 4) args.aoSamples = parsePositiveInt("AO_SAMPLES", argv[4]);
  return args;
}

std::vector<PacketSet> rendererRays(const Scene& scene, const WideBvh& bvh, int width, int aoSamples) {
  const CameraBasis basis = makeCameraBasis(scene.camera, width, width);
  const size_t count = size_t(width) * size_t(width);
  std::vector<Ray> primary(count);
  std::vector<Hit> hits(count);
  for (size_t i = 0; i < count; ++i) {
    primary[i] = primaryRay(basis, int(i % size_t(width)), int(i / size_t(width)));
    hits[i] = traverseWideBvhAvx2(bvh, scene.triangles, primary[i], false, TriangleTest::MollerTrumbore, nullptr);
  }

  // The hit point lifted off its surface along the normal facing the ray, as render/shading.cpp does.
  const float epsilon = secondaryRayEpsilon(scene), aoLength = aoDistance(scene, ShadingConfig{});
  auto lifted = [&](size_t i, glm::vec3& origin, glm::vec3& normal) {
    if (!hits[i].found()) return false;
    const glm::vec3 d = primary[i].direction;
    const glm::vec3 g = glm::normalize(scene.triangles[hits[i].id].geometricNormal());
    normal = glm::dot(g, d) > 0.0f ? -g : g;
    origin = primary[i].origin + hits[i].t * d + epsilon * normal;
    return true;
  };
  std::vector<PacketSet> sets = {{"primary", false, {}, 0}, {"shadow", true, {}, 0}, {"ao", true, {}, 0}};
  for (const std::vector<size_t>& tile : tiles(width, 8, 4)) {
    std::vector<Ray> packet;
    for (size_t i : tile) packet.push_back(primary[i]);
    add(sets[0], packet);
  }
  for (const std::vector<size_t>& tile : tiles(width, 8, 8)) {
    std::vector<Ray> shadow;
    std::vector<std::vector<Ray>> ao{size_t(aoSamples)};
    for (size_t i : tile) {
      glm::vec3 origin, normal;
      if (!lifted(i, origin, normal)) continue;
      const glm::vec3 toLight = scene.light.position - origin;
      const float distance = glm::length(toLight);
      if (glm::dot(normal, toLight) > 0.0f) shadow.push_back(Ray{origin, toLight / distance, distance});
      for (int s = 0; s < aoSamples; ++s)
        ao[size_t(s)].push_back(Ray{origin, aoDirection(normal, aoRandom(uint32_t(i), uint32_t(s))), aoLength});
    }
    add(sets[1], shadow);
    for (const std::vector<Ray>& packet : ao) add(sets[2], packet);
  }
  return sets;
}

}  // namespace passtrace
