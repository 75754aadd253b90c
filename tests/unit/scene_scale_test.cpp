// The scene scale rule (scenes/scene_scale.h) and framing of extreme bounds;
// its effect end to end is in tests/e2e/degenerate_cli_test.cpp.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/scene.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"
#include "tests/degenerate_scenes.h"

namespace passtrace {
namespace {

using test::heightField;
using test::objOf;
using test::scaledByPowerOfTwo;
using test::transformed;

// The rescaling rule itself: only scenes outside [2^-16, 2^16] move, by the
// power of two that brings their largest coordinate into [1, 2), exactly.
TEST(SceneScale, RescalesOnlyOutsideTheSafeRangeAndExactly) {
  Scene scene;
  scene.triangles = heightField(2, true);
  EXPECT_EQ(sceneScaleExponent(scene), 0);
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 16);
  EXPECT_EQ(sceneScaleExponent(scene), 0) << "2^16 is still in range";
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 17);
  EXPECT_EQ(sceneScaleExponent(scene), -17);
  scene.triangles = scaledByPowerOfTwo(heightField(2, true), -17);
  EXPECT_EQ(sceneScaleExponent(scene), 17);
  scene.triangles.assign(2, Triangle{});  // all at the origin
  EXPECT_EQ(sceneScaleExponent(scene), 0);

  scene.triangles = scaledByPowerOfTwo(heightField(2, true), 90);
  scene.camera.eye = {0, 0, std::ldexp(3.0f, 90)};
  scene.light.position = {std::ldexp(1.0f, 91), 0, 0};
  EXPECT_EQ(normalizeSceneScale(scene), -90);
  EXPECT_EQ(scene.scaleExponent, -90);
  const std::vector<Triangle> unit = heightField(2, true);
  for (size_t i = 0; i < unit.size(); ++i) EXPECT_EQ(scene.triangles[i].v1, unit[i].v1);
  EXPECT_EQ(scene.camera.eye, glm::vec3(0, 0, 3));
  EXPECT_EQ(scene.light.position, glm::vec3(2, 0, 0));
}

// Framing a scene in one point, near FLT_MAX or of subnormal size still gives
// a usable, finite view (scene_registry.cpp).
TEST(SceneScale, FramingCopesWithPointsAndExtremeBounds) {
  for (const Aabb& box : {Aabb{{1e30f, 1e30f, 1e30f}, {1e30f, 1e30f, 1e30f}}, Aabb{{-3e38f, -3e38f, 0}, {3e38f, 3e38f, 0}},
                          Aabb{{1e-40f, 0, 0}, {3e-40f, 1e-40f, 0}}, Aabb{{2, 2, 2}, {2, 2, 2}}}) {
    const CameraSpec c = framedCamera(box);
    EXPECT_NE(c.eye, c.lookAt) << box.min.x;
    EXPECT_TRUE(std::isfinite(c.lookAt.x + c.lookAt.y + c.lookAt.z)) << box.min.x;
  }
}

}  // namespace
}  // namespace passtrace
