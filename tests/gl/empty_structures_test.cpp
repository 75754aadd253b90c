// Every structure of the registry with no triangles at all, on the CPU, as
// its kernel's CPU mirror, and on the GPU.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/gpu_traversal.h"
#include "accel/registry.h"
#include "scenes/scene.h"
#include "tests/gl_test_support.h"

namespace passtrace {
namespace {

// The structures themselves with no triangles at all (the command line
// refuses empty scenes before building, but a library caller may not):
// every ray misses, nothing crashes.
class EmptyStructures : public test::GlTest {};

TEST_F(EmptyStructures, EveryStructureBuildsAndMissesWithoutTriangles) {
  Scene scene;
  scene.materials.push_back(Material{});
  std::vector<Ray> rays;
  for (int i = 0; i < 16; ++i) rays.push_back(Ray{{0, 0, 3}, glm::normalize(glm::vec3(0.1f * float(i - 8), 0.05f, -1))});
  AccelBuildConfig build;
  build.gsTries = 1;
  for (const Structure& s : structures()) {
    SCOPED_TRACE(std::string(s.name));
    if (s.cpu) {
      const auto accel = makeCpuStructure(s, scene.triangles, build);
      for (const Ray& ray : rays) EXPECT_FALSE(accel->intersect(ray, false, nullptr).found());
    }
    if (s.mirror) {
      const auto accel = makeMirrorStructure(s, scene.triangles, build);
      for (const Ray& ray : rays) EXPECT_FALSE(accel->intersect(ray, false, nullptr).found());
    }
    if (s.stream)
      for (const GridKernels kernels : {GridKernels::Merged, GridKernels::Split}) {
        const auto reads = s.readsOn(RendererId::Gpu);
        if (kernels == GridKernels::Split && std::find(reads.begin(), reads.end(), BuildParam::GridKernels) == reads.end())
          continue;
        const auto traversal = makeStreamStructure(s, scene.triangles, GpuTraversalConfig{build, 20, kernels});
        for (const Hit& hit : test::traceOnGpu(*traversal, rays).hits) EXPECT_FALSE(hit.found());
      }
  }
}

}  // namespace
}  // namespace passtrace
