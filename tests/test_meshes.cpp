#include "tests/test_meshes.h"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace passtrace::testmesh {
namespace {

// Uniform floats from the raw engine: std::uniform_real_distribution differs
// between standard libraries, and the meshes should not.
class Random {
public:
  explicit Random(uint64_t seed) : engine_(seed) {}
  float unit() { return static_cast<float>(static_cast<double>(engine_() >> 11) * 0x1.0p-53); }  // [0, 1)
  float range(float lo, float hi) { return lo + (hi - lo) * unit(); }
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(engine_() % n); }
  glm::vec3 inBox(const Aabb& b) {
    return {range(b.min.x, b.max.x), range(b.min.y, b.max.y), range(b.min.z, b.max.z)};
  }
  glm::vec3 unitVector() {
    for (;;) {
      const glm::vec3 p{range(-1, 1), range(-1, 1), range(-1, 1)};
      const float len2 = glm::dot(p, p);
      if (len2 > 1e-4f && len2 <= 1.0f) return p / std::sqrt(len2);
    }
  }

private:
  std::mt19937_64 engine_;
};

Aabb expanded(const Aabb& b, float fraction) {
  const float margin = std::max(fraction * glm::length(b.extent()), 1e-3f);
  return Aabb{b.min - glm::vec3(margin), b.max + glm::vec3(margin)};
}

}  // namespace

std::vector<Triangle> uvSphere(uint32_t rings, uint32_t segments, glm::vec3 center, float radius) {
  if (rings < 2 || segments < 3) throw std::invalid_argument("uvSphere: need rings >= 2, segments >= 3");
  auto point = [&](uint32_t ring, uint32_t segment) {
    const double theta = std::numbers::pi * ring / rings;  // 0 at the north pole
    const double phi = 2.0 * std::numbers::pi * (segment % segments) / segments;
    return center + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                       std::sin(theta) * std::sin(phi));
  };
  std::vector<Triangle> tris;
  tris.reserve(2 * size_t{segments} * (rings - 1));
  const glm::vec3 north = center + glm::vec3(0, radius, 0), south = center - glm::vec3(0, radius, 0);
  for (uint32_t s = 0; s < segments; ++s) {
    tris.push_back({north, point(1, s + 1), point(1, s)});
    for (uint32_t r = 1; r + 1 < rings; ++r) {
      tris.push_back({point(r, s), point(r, s + 1), point(r + 1, s + 1)});
      tris.push_back({point(r, s), point(r + 1, s + 1), point(r + 1, s)});
    }
    tris.push_back({south, point(rings - 1, s), point(rings - 1, s + 1)});
  }
  return tris;
}

std::vector<Triangle> triangleSoup(size_t count, const Aabb& box, float maxEdge, uint64_t seed) {
  Random rng(seed);
  std::vector<Triangle> tris;
  tris.reserve(count);
  const float h = 0.5f * maxEdge;
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 c = rng.inBox(box);
    auto vertex = [&] { return c + glm::vec3(rng.range(-h, h), rng.range(-h, h), rng.range(-h, h)); };
    const glm::vec3 a = vertex(), b = vertex(), d = vertex();
    tris.push_back({a, b, d});
  }
  return tris;
}

std::vector<Triangle> flatGrid(uint32_t cellsU, uint32_t cellsV, int normalAxis, float offset) {
  if (normalAxis < 0 || normalAxis > 2) throw std::invalid_argument("flatGrid: normalAxis must be 0, 1 or 2");
  const int ua = (normalAxis + 1) % 3, va = (normalAxis + 2) % 3;
  auto point = [&](uint32_t i, uint32_t j) {
    glm::vec3 p;
    p[normalAxis] = offset;
    p[ua] = static_cast<float>(i) / static_cast<float>(cellsU);
    p[va] = static_cast<float>(j) / static_cast<float>(cellsV);
    return p;
  };
  std::vector<Triangle> tris;
  tris.reserve(2 * size_t{cellsU} * cellsV);
  for (uint32_t j = 0; j < cellsV; ++j)
    for (uint32_t i = 0; i < cellsU; ++i) {
      tris.push_back({point(i, j), point(i + 1, j), point(i + 1, j + 1)});
      tris.push_back({point(i, j), point(i + 1, j + 1), point(i, j + 1)});
    }
  return tris;
}

std::vector<Triangle> degenerateMix(size_t count, uint64_t seed) {
  const Aabb box{glm::vec3(-1.0f), glm::vec3(1.0f)};
  std::vector<Triangle> tris = triangleSoup(count, box, 0.4f, seed);
  for (size_t i = 3; i < count; i += 4) {
    Triangle& t = tris[i];
    switch ((i / 4) % 4) {
      case 0: t = {t.v0, t.v0, t.v0}; break;                          // a point
      case 1: t = {t.v0, t.v1, t.v1}; break;                          // a segment, two vertices equal
      case 2: t = {t.v0, t.v1, t.v0 + 0.5f * (t.v1 - t.v0)}; break;  // collinear
      default: t = tris[i - 1]; break;                                // duplicate
    }
  }
  return tris;
}

std::vector<Triangle> singleTriangle() {
  return {{glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(-1, 1, 0)}};
}

std::vector<Triangle> pointMesh(size_t count, glm::vec3 point) {
  return std::vector<Triangle>(count, Triangle{point, point, point});
}

std::vector<Triangle> coincidentCentroids(size_t count, uint64_t seed, glm::vec3 center) {
  Random rng(seed);
  auto integerOffset = [&] {
    glm::vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(static_cast<int>(rng.below(9)) - 4);
    return p;
  };
  std::vector<Triangle> tris;
  tris.reserve(count);
  while (tris.size() < count) {
    const glm::vec3 a = integerOffset(), b = integerOffset(), c = -(a + b);
    if (glm::length(glm::cross(b - a, c - a)) == 0.0f) continue;  // keep them proper
    // Exact integer arithmetic, so every (v0 + v1 + v2) is the same 3 * center.
    tris.push_back({center + a, center + b, center + c});
  }
  return tris;
}

Aabb boundsOf(std::span<const Triangle> tris) {
  Aabb b;
  for (const Triangle& t : tris) b.extend(t.bounds());
  return b;
}

// (2 * cbrt(64) = 8 cells along each axis.)
std::vector<Triangle> cellBoundaryMesh() {
  std::vector<Triangle> tris;
  auto square = [&](int axis, float p, float a0, float a1, float b0, float b1) {
    auto at = [&](float a, float b) {
      glm::vec3 v;
      v[axis] = p;
      v[(axis + 1) % 3] = a;
      v[(axis + 2) % 3] = b;
      return v;
    };
    tris.push_back({at(a0, b0), at(a1, b0), at(a1, b1)});
    tris.push_back({at(a0, b0), at(a1, b1), at(a0, b1)});
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const float p : {0.0f, 3.0f, 5.0f, 8.0f}) square(axis, p, float(1 + axis), float(4 + axis), 2.0f, 6.0f);
  // 24 so far; four large ones.
  tris.push_back({glm::vec3(0, 0, 0), glm::vec3(8, 0, 8), glm::vec3(0, 8, 8)});
  tris.push_back({glm::vec3(8, 8, 0), glm::vec3(0, 8, 0), glm::vec3(8, 0, 8)});
  tris.push_back({glm::vec3(0, 0, 4), glm::vec3(8, 0, 4), glm::vec3(8, 8, 4)});  // in a cell plane
  tris.push_back({glm::vec3(1, 7, 1), glm::vec3(7, 1, 7), glm::vec3(4, 4, 1)});
  std::mt19937_64 rng(17);
  auto coord = [&] { return float(rng() % 9); };
  while (tris.size() < 64) {
    const glm::vec3 v0(coord(), coord(), coord());
    glm::vec3 v1 = v0, v2 = v0;
    const int a = int(rng() % 3), b = (a + 1 + int(rng() % 2)) % 3;
    v1[a] = coord();
    v2[b] = coord();
    if (rng() % 2) v2[a] = v1[a];  // sometimes a right triangle in a cell plane
    if (glm::cross(v1 - v0, v2 - v0) == glm::vec3(0.0f)) continue;
    tris.push_back({v0, v1, v2});
  }
  return tris;
}

std::vector<NamedMesh> standardMeshes() {
  std::vector<NamedMesh> meshes;
  meshes.push_back({"sphere", uvSphere(24, 32)});
  meshes.push_back({"soup", triangleSoup(3000, Aabb{glm::vec3(-2.0f), glm::vec3(2.0f)}, 0.3f, 7)});
  meshes.push_back({"gridZ", flatGrid(24, 16, 2, 0.25f)});
  meshes.push_back({"gridX", flatGrid(8, 8, 0, -1.0f)});
  meshes.push_back({"degenerate", degenerateMix(800, 11)});
  meshes.push_back({"single", singleTriangle()});
  meshes.push_back({"coincident", coincidentCentroids(300, 13)});
  return meshes;
}

std::vector<NamedMesh> standardMeshesAndCellBoundaries() {
  std::vector<NamedMesh> all = standardMeshes();
  all.push_back({"cellBoundaries", cellBoundaryMesh()});
  return all;
}

std::vector<Ray> makeRays(RayKind kind, const Aabb& bounds, size_t count, uint64_t seed, bool finiteTMax) {
  Random rng(seed);
  const Aabb box = expanded(bounds, 0.1f);
  const glm::vec3 center = box.center();
  const float diagonal = glm::length(box.extent());
  std::vector<Ray> rays;
  rays.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    Ray ray;
    switch (kind) {
      case RayKind::OutsideIn: {
        ray.origin = center + diagonal * rng.unitVector();
        ray.direction = glm::normalize(rng.inBox(box) - ray.origin);
        break;
      }
      case RayKind::Inside: {
        ray.origin = rng.inBox(box);
        ray.direction = rng.unitVector();
        break;
      }
      case RayKind::AxisAligned: {
        const uint32_t axis = rng.below(3);
        const float sign = rng.below(2) ? 1.0f : -1.0f;
        ray.origin = rng.inBox(box);
        if (rng.below(2))  // start outside, on the side the ray comes from
          ray.origin[axis] = sign > 0 ? box.min[axis] - 0.5f * diagonal : box.max[axis] + 0.5f * diagonal;
        ray.direction = glm::vec3(0.0f);
        ray.direction[axis] = sign;
        break;
      }
      case RayKind::FaceParallel: {
        const uint32_t zero = rng.below(3);
        ray.origin = rng.inBox(box);
        glm::vec3 d = rng.unitVector();
        d[zero] = 0.0f;
        if (glm::dot(d, d) < 1e-6f) d[(zero + 1) % 3] = 1.0f;
        ray.direction = glm::normalize(d);
        ray.direction[zero] = 0.0f;  // stays exactly zero (normalize keeps it, but be explicit)
        break;
      }
    }
    if (finiteTMax) ray.tMax = rng.unit() * (glm::length(ray.origin - center) + diagonal);
    rays.push_back(ray);
  }
  return rays;
}

std::vector<Ray> rayMix(const Aabb& bounds, size_t countPerKind, uint64_t seed) {
  std::vector<Ray> rays;
  const RayKind kinds[] = {RayKind::OutsideIn, RayKind::Inside, RayKind::AxisAligned, RayKind::FaceParallel};
  uint64_t stream = seed;
  for (const RayKind kind : kinds)
    for (const bool finite : {false, true}) {
      const std::vector<Ray> part = makeRays(kind, bounds, (countPerKind + finite) / 2, ++stream * 0x9e3779b97f4a7c15ull, finite);
      rays.insert(rays.end(), part.begin(), part.end());
    }
  return rays;
}

std::vector<Triangle> longThinTriangles(size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Triangle> tris;
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 a(unit(rng) * 0.1f, unit(rng) * 0.1f, unit(rng));
    const glm::vec3 b(10.0f - unit(rng) * 0.1f, 10.0f - unit(rng) * 0.1f, unit(rng));
    tris.push_back({a, b, a + glm::vec3(0.02f, 0.0f, 0.01f)});
  }
  return tris;
}

}  // namespace passtrace::testmesh
