#include "scenes/sphere_field.h"

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene_error.h"

namespace passtrace {
namespace {

constexpr int kSpheresPerSide = 10;
constexpr uint64_t kSpheres = kSpheresPerSide * kSpheresPerSide;
constexpr uint64_t kGroundTriangles = 2;

// A cube sphere: each cube face an n x n grid of quads (two triangles),
// projected onto the sphere. Unlike a UV sphere it has no poles, whose fans
// of sliver triangles get unreliable geometric normals at millions of
// triangles. Shared vertices come from the same integer grid point, so they
// are bit-identical and the mesh is closed.
uint64_t trianglesPerSphere(int n) { return 12ull * uint64_t(n) * uint64_t(n); }

int gridFor(uint64_t requested) {
  int n = 1;
  while (kSpheres * trianglesPerSphere(n) + kGroundTriangles < requested) ++n;
  return n;
}

void appendCubeSphere(const glm::vec3& centre, float radius, int n, std::vector<Triangle>& out) {
  const auto coordinate = [n](int i) { return -1.0f + 2.0f * float(i) / float(n); };
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      // The face's two in-plane axes, ordered so that triangles wind
      // counter-clockwise seen from outside.
      const int u = (axis + (side > 0 ? 1 : 2)) % 3, v = (axis + (side > 0 ? 2 : 1)) % 3;
      const auto point = [&](int i, int j) {
        glm::vec3 p;
        p[axis] = side;
        p[u] = coordinate(i);
        p[v] = coordinate(j);
        return centre + radius * glm::normalize(p);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const glm::vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
          out.push_back({a, b, c});
          out.push_back({a, c, d});
        }
    }
}

void checkRange(uint64_t requested) {
  if (requested < kSphereFieldMinTriangles || requested > kSphereFieldMaxTriangles)
    throw SceneError("spheres: --triangles " + std::to_string(requested) + " is outside [" +
                     std::to_string(kSphereFieldMinTriangles) + ", " + std::to_string(kSphereFieldMaxTriangles) + "]");
}

}  // namespace

uint64_t sphereFieldTriangles(uint64_t requested) {
  checkRange(requested);
  return kSpheres * trianglesPerSphere(gridFor(requested)) + kGroundTriangles;
}

Scene makeSphereField(uint64_t requested) {
  const uint64_t total = sphereFieldTriangles(requested);
  const int n = gridFor(requested);
  Scene scene;
  scene.name = "spheres";
  scene.materials = {Material{glm::vec3(0.55f, 0.55f, 0.5f)},                      // ground
                     Material{glm::vec3(0.8f, 0.3f, 0.2f)}, Material{glm::vec3(0.2f, 0.5f, 0.8f)},
                     Material{glm::vec3(0.3f, 0.7f, 0.3f)}, Material{glm::vec3(0.0f), glm::vec3(0.9f)}};  // mirror
  scene.triangles.reserve(total);
  scene.materialIds.reserve(total);

  // Ground: a square under the field, spacing 1 between sphere centres.
  const float half = 0.5f * kSpheresPerSide + 1.0f;
  const glm::vec3 a(-half, 0.0f, -half), b(half, 0.0f, -half), c(half, 0.0f, half), d(-half, 0.0f, half);
  scene.triangles.push_back({a, c, b});
  scene.triangles.push_back({a, d, c});
  scene.materialIds.assign(2, 0);

  for (int i = 0; i < kSpheresPerSide; ++i)
    for (int j = 0; j < kSpheresPerSide; ++j) {
      // Radii 0.25..0.45 in a fixed pattern; the spheres rest on the ground.
      const float radius = 0.25f + 0.05f * float((i * 7 + j * 3) % 5);
      const glm::vec3 centre(float(i) - 0.5f * (kSpheresPerSide - 1), radius, float(j) - 0.5f * (kSpheresPerSide - 1));
      const bool mirror = i == kSpheresPerSide / 2 && j == kSpheresPerSide / 2;
      const uint32_t material = mirror ? 4u : 1u + uint32_t((i + 2 * j) % 3);
      appendCubeSphere(centre, radius, n, scene.triangles);
      scene.materialIds.resize(scene.triangles.size(), material);
    }
  if (scene.triangles.size() != total)
    throw SceneError("spheres: internal error: made " + std::to_string(scene.triangles.size()) + " triangles, expected " +
                     std::to_string(total));

  scene.camera = CameraSpec{{0.0f, 5.5f, 11.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  scene.light = PointLight{{4.0f, 10.0f, 6.0f}, glm::vec3(1.0f)};
  scene.background = {0.1f, 0.12f, 0.16f};
  scene.ambient = 0.1f;
  return scene;
}

}  // namespace passtrace
