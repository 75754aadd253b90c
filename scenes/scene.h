#pragma once
// The scene every renderer and accelerator consumes: a flat triangle soup in
// scene order (a triangle's index is its id in hit records), optional vertex
// normals, one material per triangle, one point light and a default view.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace {

// A material is either diffuse or a perfect mirror (thesis 4.2: no refraction).
struct Material {
  glm::vec3 diffuse{0.8f};  // C in (N.L)C
  glm::vec3 mirror{0.0f};   // reflectance; non-zero makes the material a mirror
  // Read by --shading whitted only (the thesis rules ignore them):
  glm::vec3 specular{0.0f};  // Phong highlight colour Ks (0: no highlight)
  float shininess = 1.0f;    // Phong exponent
  float transmission = 0.0f;  // fraction of light refracted through (0 opaque, 1 clear glass)
  float ior = 1.5f;           // index of refraction (glTF KHR_materials_ior's default)
  bool isMirror() const { return mirror.r > 0.0f || mirror.g > 0.0f || mirror.b > 0.0f; }
};

struct PointLight {
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
};

// The camera of the interface contract: vertical field of view in degrees.
struct CameraSpec {
  glm::vec3 eye{0.0f, 0.0f, 3.0f};
  glm::vec3 lookAt{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovDegrees = 45.0f;
};

// A span of animation time (--time, --time-start/--time-end), start <= end.
struct TimeRange {
  float start = 0.0f, end = 0.0f;
};

struct Scene {
  std::string name;
  // Every vertex is finite. The rule for non-finite input, in every loader:
  // reject, never drop. A NaN or infinite number in the file, or a vertex that
  // becomes non-finite only after transforms or tessellation (an AFF `xs`
  // scale of 1e30, nested transforms, glTF node matrices whose product
  // overflows), throws SceneError naming the file and the line of the
  // command that made the triangle (glTF: "FILE: mesh M primitive P: ...").
  // Zero-area and duplicate triangles are kept as valid geometry: the first
  // is never hit; of duplicates, every structure reports the same t, and
  // which one's id depends on its traversal order (deterministic per
  // structure; brute force reports the lowest).
  std::vector<Triangle> triangles;  // scene order: the index is the hit id
  // Either empty (shade with the geometric normal) or one entry per triangle.
  std::vector<std::array<glm::vec3, 3>> vertexNormals;
  std::vector<uint32_t> materialIds;  // one per triangle, indexes materials
  std::vector<Material> materials;    // at least one
  PointLight light;
  // Every point light of the file where it has several (AFF `l` lines), for
  // --shading whitted's shadow rays; `light` is then their sum at the first
  // one's position (the thesis rules' one light). Empty: `light` alone.
  std::vector<PointLight> lights;
  // The file has no light: `light` was framed on the bounds from outside
  // (framedLight), and a view from inside gets one of its own
  // (scenes/scene_lights.h).
  bool lightIsDefault = false;
  glm::vec3 background{0.0f};
  float ambient = 0.1f;  // fraction of C added regardless of the light
  CameraSpec camera;     // the scene's default view
  // Benchmarked from this one view only (thesis 10.1.1: Robots, Kitchen and
  // the Cornell box); other scenes follow the camera path for -n angles.
  bool fixedView = false;
  // The scene's coordinates (vertices, camera, light) are the file's times
  // 2^scaleExponent: loadScene brings far-off scales into single precision's
  // safe range by this exact factor (scenes/scene_scale.h); 0 for most scenes.
  int scaleExponent = 0;
  // The times the file animates over (AFF's `a` line or its keyframes, glTF's
  // animation keys); none for a still scene. --frames spans it by default.
  std::optional<TimeRange> animation;
  // One flag per triangle: 1 where the triangle moves over the animation (an
  // animated transform above it, or animated morph weights), 0 where it is
  // static geometry. Empty: nothing moves.
  std::vector<uint8_t> moving;

  Aabb bounds() const;
  bool hasVertexNormals() const { return !vertexNormals.empty(); }
};

}  // namespace passtrace
