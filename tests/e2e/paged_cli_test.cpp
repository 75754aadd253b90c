// Paged data through the command line: whole frames that give the same bits
// with and without paging on every GPU structure of the registry, the
// procedural scene with its data in several textures against brute force,
// and the refusal of scenes too large for the machine's memory.

#include <string>

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "scenes/scene_registry.h"
#include "tests/cli_support.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

// Whole frames (three bounces on the Cornell box, whose mirror and shadows
// read the shading data at every bounce) give the same bits with 32-texel
// pages and 3 steps per pass as with one texture per stream and 20 steps, on
// every GPU structure of the registry with each --grid-kernels variant.
using Cli = test::CliTest;

TEST_F(Cli, PagedDataRendersTheSameBits) {
  for (const auto& [renderer, accel] : testing_registry::everyStructureRun()) {
    if (renderer != int(RendererId::Gpu)) continue;
    SCOPED_TRACE(accel);
    const std::string common = "-s cornell -r 2 -w 40 -b 3 -a " + accel;
    ASSERT_EQ(run(common + " -o " + path("one.exr") + " --hits " + path("one-hits.exr")).status, 0);
    // 32 texels per page, or the smallest power of two above it whose pages a
    // kernel can bind (at 32, bvh-octant's eight sequences take 16 pages: more
    // than any other stream may have, as its large stream).
    test::RunResult paged;
    for (int page = 32; page <= 1024; page *= 2) {
      paged = run(common + " --page-texels " + std::to_string(page) + " -l 3 -o " + path("paged.exr") + " --hits " +
                  path("paged-hits.exr"));
      if (paged.status == 0 || paged.err.find("a kernel reads at most") == std::string::npos) break;
    }
    ASSERT_EQ(paged.status, 0) << paged.err;
    EXPECT_EQ(test::slurp(path("one.exr")), test::slurp(path("paged.exr")));
    EXPECT_EQ(test::slurp(path("one-hits.exr")), test::slurp(path("paged-hits.exr")));
  }
}

// A GPU render of the procedural scene with its data in several textures
// against brute force, through the command line.
TEST_F(Cli, PagedSpheresHitsEqualBruteForce) {
  SceneOptions options;
  options.triangles = 20000;
  const Scene scene = loadScene("spheres", options);
  const test::RunResult r =
      run("-s spheres --triangles 20000 -r 2 -a 0 -b 1 -w 40 --page-texels 32768 --hits " + path("h.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  test::expectHitsMatchBruteForce(path("h.exr"), scene, 40);
}

// A scene that cannot fit is refused before anything is built.
TEST_F(Cli, SceneTooLargeForMemoryIsRefusedBeforeBuilding) {
  const std::string outs = " -o " + path("x.png") + " --hits " + path("x.exr");
  expectOneLineError(run("-s spheres --triangles 400000000 -r 2 -a grid" + outs), "nothing was built");
  expectOneLineError(run("-s spheres --triangles 400000000 -r 1 -a kd-pbrt" + outs), "GiB available");
  expectOneLineError(run("-s spheres --triangles 999" + outs), "--triangles");
}

}  // namespace
}  // namespace passtrace
