#pragma once
// The choice of ray/triangle test (--triangle-test): Möller–Trumbore
// (geometry.h, the thesis's and the default) or the watertight test of Woop,
// Benthin and Wald (watertight_triangle.h), which never lets a ray slip
// through the shared edge of two triangles. Every CPU traversal takes the
// choice from AccelBuildConfig; the GPU kernels get it as the define
// WATERTIGHT_TRIANGLES (kernels_glsl/intersect.glsl).

#include <optional>
#include <string>
#include <string_view>

#include "accel/geometry/geometry.h"
#include "accel/geometry/watertight_triangle.h"

namespace passtrace {

enum class TriangleTest { MollerTrumbore, Watertight };

inline constexpr const char* kTriangleTestNames[] = {"moller-trumbore", "watertight"};

inline std::string triangleTestName(TriangleTest test) { return kTriangleTestNames[int(test)]; }

// "moller-trumbore" or "watertight"; nullopt for anything else.
inline std::optional<TriangleTest> triangleTestByName(std::string_view name) {
  if (name == kTriangleTestNames[0]) return TriangleTest::MollerTrumbore;
  if (name == kTriangleTestNames[1]) return TriangleTest::Watertight;
  return std::nullopt;
}

// intersectTriangle with the chosen test; same contract as both.
inline bool intersectTriangle(const glm::vec3& origin, const glm::vec3& dir, const Triangle& tri, uint32_t id,
                              Hit& best, TriangleTest test) {
  return test == TriangleTest::Watertight ? intersectTriangleWatertight(origin, dir, tri, id, best)
                                          : intersectTriangle(origin, dir, tri, id, best);
}

// The GLSL define a kernel that intersects triangles is compiled with;
// intersect.glsl looks only for WATERTIGHT_TRIANGLES.
inline std::string triangleTestDefine(TriangleTest test) {
  return test == TriangleTest::Watertight ? "WATERTIGHT_TRIANGLES" : "MOLLER_TRUMBORE_TRIANGLES";
}

}  // namespace passtrace
