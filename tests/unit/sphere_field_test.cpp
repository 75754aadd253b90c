// The procedural "spheres" scene of any size (scenes/sphere_field.h).

#include <cstdint>

#include <gtest/gtest.h>

#include "scenes/sphere_field.h"

namespace passtrace {
namespace {

// The procedural scene of any size: exactly the promised count, at least the
// requested one, the same triangles on every call.
TEST(SphereField, CountIsPredictedAndDeterministic) {
  for (uint64_t requested : {1000ull, 123456ull}) {
    const Scene a = makeSphereField(requested), b = makeSphereField(requested);
    EXPECT_EQ(a.triangles.size(), sphereFieldTriangles(requested));
    EXPECT_GE(a.triangles.size(), requested);
    EXPECT_LT(a.triangles.size(), requested * 5 / 4 + 2400);  // about the next finer tessellation
    ASSERT_EQ(a.materialIds.size(), a.triangles.size());
    for (size_t i = 0; i < a.triangles.size(); i += 997) {
      EXPECT_EQ(a.triangles[i].v0, b.triangles[i].v0);
      EXPECT_EQ(a.triangles[i].v2, b.triangles[i].v2);
    }
  }
}

}  // namespace
}  // namespace passtrace
