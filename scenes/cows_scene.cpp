#include "scenes/cows_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/obj_loader.h"
#include "scenes/scene_error.h"
#include "scenes/tessellate.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

enum CowsMaterial : uint32_t { kGround = 0, kMirror = 1, kBark = 2, kLeaves = 3, kBunny = 4 };

// Uniform floats in [0, 1) from mt19937's raw output (the standard's
// distributions differ between libraries; the engine does not).
class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}
  float uniform() { return static_cast<float>(engine_() >> 8) * (1.0f / 16777216.0f); }
  float between(float a, float b) { return a + (b - a) * uniform(); }

 private:
  std::mt19937 engine_;
};

void append(Scene& scene, const TriangleList& list, uint32_t material) {
  scene.triangles.insert(scene.triangles.end(), list.triangles.begin(), list.triangles.end());
  scene.vertexNormals.insert(scene.vertexNormals.end(), list.normals.begin(), list.normals.end());
  scene.materialIds.insert(scene.materialIds.end(), list.triangles.size(), material);
}

void quad(Scene& scene, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
          uint32_t material) {
  TriangleList list;
  triangulateFan({a, b, c, d}, {}, list);
  append(scene, list, material);
}

// An SPD-tree-like recursive tree: each branch a tapered cone (8 sides for
// the trunk, 6 above), three children spread 120 degrees apart and tilted
// away from the parent, each 0.7 as long and 0.55 as thick, small
// octahedral leaves at the tips.
class TreeBuilder {
 public:
  explicit TreeBuilder(int levels) : levels_(levels), random_(2005) {}

  void branch(const glm::vec3& base, const glm::vec3& dir, float length, float radius, int level) {
    const glm::vec3 top = base + length * dir;
    const float topRadius = radius * (level + 1 < levels_ ? 0.7f : 0.35f);
    tessellateCone(base, radius, top, topRadius, bark, level == 0 ? 8 : 6);
    if (level + 1 == levels_) {
      leaf(top, 0.35f * length);
      return;
    }
    // A frame around dir.
    const glm::vec3 helper = std::fabs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(dir, helper));
    const glm::vec3 v = glm::cross(dir, u);
    const float phase = random_.between(0.0f, glm::two_pi<float>());
    for (int k = 0; k < 3; ++k) {
      const float azimuth = phase + glm::two_pi<float>() * static_cast<float>(k) / 3.0f + random_.between(-0.3f, 0.3f);
      const float tilt = glm::radians(random_.between(28.0f, 42.0f));
      const glm::vec3 side = std::cos(azimuth) * u + std::sin(azimuth) * v;
      glm::vec3 child = glm::normalize(std::cos(tilt) * dir + std::sin(tilt) * side);
      child = glm::normalize(child + glm::vec3(0.0f, 0.15f, 0.0f));  // a little phototropism
      branch(top, child, length * random_.between(0.62f, 0.76f), radius * 0.55f, level + 1);
    }
  }

  TriangleList bark, leaves;

 private:
  void leaf(const glm::vec3& centre, float size) {
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    const float s = size * random_.between(0.8f, 1.2f);
    for (const auto& f : faces) {
      const Triangle t{centre + s * axes[f[0]], centre + s * axes[f[1]], centre + s * axes[f[2]]};
      leaves.triangles.push_back(t);
      leaves.normals.push_back({axes[f[0]], axes[f[1]], axes[f[2]]});
    }
  }

  int levels_;
  Random random_;
};

// The bunny decimated by vertex clustering on a grid of `cells` along its
// longest side: each corner moves to the mean of its cell, triangles that
// collapse or repeat are dropped, normals are the area-weighted means of the
// kept faces around each cell. Centred on x/z, standing on y = 0, 1 unit tall.
TriangleList decimatedBunny(const fs::path& path, int cells) {
  const Scene bunny = loadObj(path);
  const Aabb box = bunny.bounds();
  const float cell = std::max({box.extent().x, box.extent().y, box.extent().z}) / static_cast<float>(cells);
  using Key = std::tuple<int, int, int>;
  std::map<Key, uint32_t> ids;
  std::vector<glm::dvec3> sums;
  std::vector<uint32_t> counts;
  std::vector<std::array<uint32_t, 3>> faces;
  faces.reserve(bunny.triangles.size());
  const auto idOf = [&](const glm::vec3& p) {
    const glm::vec3 q = (p - box.min) / cell;
    const Key key{static_cast<int>(std::floor(q.x)), static_cast<int>(std::floor(q.y)), static_cast<int>(std::floor(q.z))};
    const auto [it, fresh] = ids.emplace(key, static_cast<uint32_t>(sums.size()));
    if (fresh) {
      sums.emplace_back(0.0);
      counts.push_back(0);
    }
    sums[it->second] += glm::dvec3(p);
    ++counts[it->second];
    return it->second;
  };
  for (const Triangle& t : bunny.triangles) faces.push_back({idOf(t.v0), idOf(t.v1), idOf(t.v2)});

  std::vector<glm::vec3> points(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i) points[i] = glm::vec3(sums[i] / static_cast<double>(counts[i]));
  std::vector<std::array<uint32_t, 3>> kept;
  std::map<std::array<uint32_t, 3>, bool> seen;
  for (const auto& f : faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    std::array<uint32_t, 3> sorted = f;
    std::sort(sorted.begin(), sorted.end());
    if (!seen.emplace(sorted, true).second) continue;
    kept.push_back(f);
  }
  std::vector<glm::vec3> normals(points.size(), glm::vec3(0.0f));
  for (const auto& f : kept) {
    const glm::vec3 n = glm::cross(points[f[1]] - points[f[0]], points[f[2]] - points[f[0]]);
    for (uint32_t i : f) normals[i] += n;
  }
  for (glm::vec3& n : normals) n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0);

  // Normalise placement: 1 unit tall, centred, on the ground.
  Aabb kb;
  for (const auto& f : kept)
    for (uint32_t i : f) kb.extend(points[i]);
  const float scale = 1.0f / std::max(kb.extent().y, 1e-6f);
  const glm::vec3 offset(-kb.center().x, -kb.min.y, -kb.center().z);
  TriangleList out;
  for (const auto& f : kept) {
    out.triangles.push_back({scale * (points[f[0]] + offset), scale * (points[f[1]] + offset), scale * (points[f[2]] + offset)});
    out.normals.push_back({normals[f[0]], normals[f[1]], normals[f[2]]});
  }
  return out;
}

// The stand-in when the bunny is missing: a lumpy sphere, 1 unit tall.
TriangleList blob() {
  TriangleList out;
  tessellateSphere(glm::vec3(0.0f, 0.5f, 0.0f), 0.5f, out, 40, 20);
  for (std::size_t i = 0; i < out.triangles.size(); ++i) {
    glm::vec3* v[3] = {&out.triangles[i].v0, &out.triangles[i].v1, &out.triangles[i].v2};
    for (glm::vec3* p : v) {
      const glm::vec3 d = *p - glm::vec3(0.0f, 0.5f, 0.0f);
      *p = glm::vec3(0.0f, 0.5f, 0.0f) + d * (1.0f + 0.12f * std::sin(5.0f * d.x / 0.5f) * std::cos(4.0f * d.z / 0.5f));
    }
  }
  return out;
}

}  // namespace

Scene makeCowsScene(const fs::path& bunnyPath) {
  Scene scene;
  scene.name = "cows";
  scene.materials = {
      Material{glm::vec3(0.55f, 0.6f, 0.45f), glm::vec3(0.0f)},   // ground
      Material{glm::vec3(0.1f), glm::vec3(0.85f)},                // mirror back plane
      Material{glm::vec3(0.45f, 0.32f, 0.2f), glm::vec3(0.0f)},   // bark
      Material{glm::vec3(0.25f, 0.55f, 0.2f), glm::vec3(0.0f)},   // leaves
      Material{glm::vec3(0.85f, 0.8f, 0.72f), glm::vec3(0.0f)},   // bunnies
  };

  // Ground (y = 0) and the mirror back plane (z = -10), facing the camera.
  quad(scene, {-14, 0, 8}, {14, 0, 8}, {14, 0, -10}, {-14, 0, -10}, kGround);
  quad(scene, {-14, 0, -10}, {14, 0, -10}, {14, 12, -10}, {-14, 12, -10}, kMirror);

  TreeBuilder tree(7);
  tree.branch(glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(0.0f, 1.0f, 0.0f), 3.0f, 0.45f, 0);
  append(scene, tree.bark, kBark);
  append(scene, tree.leaves, kLeaves);

  std::error_code ignored;
  const TriangleList animal = fs::exists(bunnyPath, ignored) ? decimatedBunny(bunnyPath, 25) : blob();
  struct Placement {
    glm::vec3 position;
    float yawDegrees, height;
  };
  for (const Placement& p : {Placement{{-4.5f, 0.0f, 1.5f}, 30.0f, 1.8f}, Placement{{4.0f, 0.0f, 0.5f}, -40.0f, 1.5f},
                             Placement{{-0.5f, 0.0f, 3.5f}, 160.0f, 1.2f}}) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), p.position);
    m = glm::rotate(m, glm::radians(p.yawDegrees), glm::vec3(0, 1, 0));
    m = glm::scale(m, glm::vec3(p.height));
    const glm::mat3 rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(p.yawDegrees), glm::vec3(0, 1, 0)));
    TriangleList placed;
    for (std::size_t i = 0; i < animal.triangles.size(); ++i) {
      const Triangle& t = animal.triangles[i];
      placed.triangles.push_back({glm::vec3(m * glm::vec4(t.v0, 1)), glm::vec3(m * glm::vec4(t.v1, 1)),
                                  glm::vec3(m * glm::vec4(t.v2, 1))});
      placed.normals.push_back({rotation * animal.normals[i][0], rotation * animal.normals[i][1],
                                rotation * animal.normals[i][2]});
    }
    append(scene, placed, kBunny);
  }

  scene.camera = CameraSpec{{0.0f, 4.5f, 15.0f}, {0.0f, 3.2f, -3.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  scene.light = PointLight{{7.0f, 14.0f, 9.0f}, glm::vec3(1.0f)};
  scene.background = {0.55f, 0.7f, 0.9f};
  scene.ambient = 0.15f;
  return scene;
}

}  // namespace passtrace
