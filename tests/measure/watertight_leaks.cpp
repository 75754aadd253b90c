// The watertightness measurement (docs/measurements.md#watertightness): rays
// from inside the jittered sphere of tests/gl/watertight_test.cpp through
// every structure of the registry on the CPU and GPU renderers, with both
// triangle tests, and Embree; one line of leaks per run. The test asserts the
// bounds; this prints the rates.
//
//   build/tests/measure/measure_watertight_leaks [rays per structure, default 3000000]

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "accel/gpu_traversal.h"
#include "accel/registry.h"
#include "accel/geometry/triangle_test.h"
#include "tests/gl_test_support.h"
#include "tests/watertight_sphere.h"

namespace {

using namespace passtrace;

std::vector<Hit> traceCpu(const CpuAccelerator& accel, const std::vector<Ray>& rays) {
  std::vector<Hit> hits(rays.size());
  const size_t threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (size_t t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (size_t i = t; i < rays.size(); i += threads) hits[i] = accel.intersect(rays[i], false, nullptr);
    });
  for (std::thread& th : pool) th.join();
  return hits;
}

std::vector<Hit> traceGpu(GpuTraversal& traversal, const std::vector<Ray>& rays) {
  constexpr size_t kBatch = 64 * 8192;  // under the 16384-row texture limit
  std::vector<Hit> hits;
  for (size_t begin = 0; begin < rays.size(); begin += kBatch) {
    const std::vector<Ray> batch(rays.begin() + begin, rays.begin() + std::min(rays.size(), begin + kBatch));
    const auto traced = test::traceOnGpu(traversal, batch);
    hits.insert(hits.end(), traced.hits.begin(), traced.hits.end());
  }
  return hits;
}

void printLeaks(const char* renderer, const std::string& structure, const std::string& test,
                const std::vector<Hit>& hits) {
  size_t leaks[testmesh::kInsideRayKinds] = {0, 0, 0};
  for (size_t i = 0; i < hits.size(); ++i) leaks[i % testmesh::kInsideRayKinds] += !hits[i].found();
  const size_t total = leaks[0] + leaks[1] + leaks[2];
  std::printf("| %s | %s | %s | %zu | %zu | %zu | %zu | %.3g |\n", renderer, structure.c_str(), test.c_str(),
              hits.size(), leaks[0], leaks[1], leaks[2], double(total) / double(hits.size()));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const long long count = argc > 1 ? std::atoll(argv[1]) : 3'000'000;
  if (count <= 0) {
    std::fprintf(stderr, "usage: %s [rays per structure]\n", argv[0]);
    return 2;
  }
  // The test's sphere and rays (tests/gl/watertight_test.cpp).
  const testmesh::JitteredSphere sphere = testmesh::jitteredSphere(180, 360, 0.005f, 2013);
  const std::vector<Ray> rays = testmesh::insideRays(sphere, size_t(count), 0.5f, 77);
  test::glContext();  // the GPU runs' context
  std::printf("| renderer | structure | triangle test | rays | leaks uniform | at edges | at vertices | rate |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const TriangleTest test : {TriangleTest::MollerTrumbore, TriangleTest::Watertight}) {
    AccelBuildConfig build;
    build.gsTries = 1;
    build.triangleTest = test;
    for (const Structure& s : structures()) {
      if (!s.runsOn(RendererId::Cpu)) continue;
      printLeaks("cpu", std::string(s.name), triangleTestName(test), traceCpu(*makeCpuStructure(s, sphere.tris, build), rays));
    }
    for (const Structure& s : structures()) {
      if (!s.runsOn(RendererId::Gpu)) continue;
      const auto reads = s.readsOn(RendererId::Gpu);
      for (const GridKernels kernels : {GridKernels::Merged, GridKernels::Split}) {
        if (kernels == GridKernels::Split && std::find(reads.begin(), reads.end(), BuildParam::GridKernels) == reads.end())
          continue;
        const auto traversal = makeStreamStructure(s, sphere.tris, GpuTraversalConfig{build, 64, kernels});
        printLeaks("gpu", std::string(s.name) + (kernels == GridKernels::Split ? " (split)" : ""),
                   triangleTestName(test), traceGpu(*traversal, rays));
      }
    }
  }
  for (const Structure& s : structures())
    if (s.runsOn(RendererId::Embree))
      printLeaks("embree", std::string(s.name), "embree's own", traceCpu(*makeCpuStructure(s, sphere.tris), rays));
  return 0;
}
