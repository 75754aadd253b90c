#include "tests/watertight_sphere.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace passtrace::testmesh {
namespace {

// splitmix64: a fixed generator, so the mesh and rays are the same with
// every standard library (std:: distributions are not).
class SplitMix {
 public:
  explicit SplitMix(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float unit() { return float(double(next() >> 11) * 0x1.0p-53); }  // [0, 1)
  float range(float lo, float hi) { return lo + (hi - lo) * unit(); }
  uint32_t below(size_t n) { return uint32_t(next() % n); }

 private:
  uint64_t state_;
};

}  // namespace

JitteredSphere jitteredSphere(uint32_t rings, uint32_t segments, float jitter, uint64_t seed) {
  if (rings < 2 || segments < 3) throw std::invalid_argument("jitteredSphere: need rings >= 2, segments >= 3");
  SplitMix random(seed);
  JitteredSphere s;
  s.minRadius = kInfinity;
  s.maxRadius = 0.0f;
  auto addVertex = [&](double theta, double phi) {
    const float r = 1.0f + jitter * random.range(-1.0f, 1.0f);
    const glm::vec3 normal(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    s.vertices.push_back(r * normal);
    s.minRadius = std::min(s.minRadius, glm::length(s.vertices.back()));
    s.maxRadius = std::max(s.maxRadius, glm::length(s.vertices.back()));
    return uint32_t(s.vertices.size() - 1);
  };
  // Vertex 0 is the north pole, then rings 1..rings-1 of `segments` each, then the south pole.
  const uint32_t north = addVertex(0.0, 0.0);
  for (uint32_t ring = 1; ring < rings; ++ring)
    for (uint32_t seg = 0; seg < segments; ++seg)
      addVertex(std::numbers::pi * ring / rings, 2.0 * std::numbers::pi * seg / segments);
  const uint32_t south = addVertex(std::numbers::pi, 0.0);
  auto at = [&](uint32_t ring, uint32_t seg) { return 1 + (ring - 1) * segments + seg % segments; };

  std::vector<glm::uvec3> faces;
  for (uint32_t seg = 0; seg < segments; ++seg) {
    faces.push_back({north, at(1, seg + 1), at(1, seg)});
    for (uint32_t ring = 1; ring + 1 < rings; ++ring) {
      faces.push_back({at(ring, seg), at(ring, seg + 1), at(ring + 1, seg + 1)});
      faces.push_back({at(ring, seg), at(ring + 1, seg + 1), at(ring + 1, seg)});
    }
    faces.push_back({south, at(rings - 1, seg), at(rings - 1, seg + 1)});
    // The edges, each once: along the ring, down to the next ring, and the diagonal.
    s.edges.push_back({north, at(1, seg)});
    for (uint32_t ring = 1; ring < rings; ++ring) {
      s.edges.push_back({at(ring, seg), at(ring, seg + 1)});
      s.edges.push_back({at(ring, seg), ring + 1 < rings ? at(ring + 1, seg) : south});
      if (ring + 1 < rings) s.edges.push_back({at(ring, seg), at(ring + 1, seg + 1)});
    }
  }
  // Expanded from the indexed form: shared corners are bit-identical.
  s.tris.reserve(faces.size());
  for (const glm::uvec3& f : faces) s.tris.push_back({s.vertices[f.x], s.vertices[f.y], s.vertices[f.z]});
  return s;
}

std::vector<Ray> insideRays(const JitteredSphere& sphere, size_t count, float originRadius, uint64_t seed) {
  SplitMix random(seed);
  std::vector<Ray> rays(count);
  for (size_t i = 0; i < count; ++i) {
    glm::vec3 origin;
    do {
      origin = glm::vec3(random.range(-1, 1), random.range(-1, 1), random.range(-1, 1));
    } while (glm::dot(origin, origin) > 1.0f);
    origin *= originRadius;
    glm::vec3 target;
    switch (InsideRayKind(i % kInsideRayKinds)) {
      case InsideRayKind::Uniform: {
        const float z = random.range(-1.0f, 1.0f);
        const float phi = random.range(0.0f, 2.0f * std::numbers::pi_v<float>);
        const float rho = std::sqrt(std::max(0.0f, 1.0f - z * z));
        target = origin + glm::vec3(rho * std::cos(phi), rho * std::sin(phi), z);
        break;
      }
      case InsideRayKind::AtEdge: {
        const glm::uvec2 e = sphere.edges[random.below(sphere.edges.size())];
        const float f = random.unit();
        target = sphere.vertices[e.x] + f * (sphere.vertices[e.y] - sphere.vertices[e.x]);
        break;
      }
      case InsideRayKind::AtVertex:
        target = sphere.vertices[random.below(sphere.vertices.size())];
        break;
    }
    rays[i] = Ray{origin, glm::normalize(target - origin), kInfinity};
  }
  return rays;
}

}  // namespace passtrace::testmesh
