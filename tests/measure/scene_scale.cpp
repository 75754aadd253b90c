// The measurement behind scenes/scene_scale.h: the bunny scaled by 1e-30 ...
// 1e30 through every structure of every renderer, without ("raw": loadObj
// and framing only) and with loadScene's rescaling, against the unit bunny's
// hits on the same structure. Prints the pixels (of 32x32) whose hit differs.
//
//   build/tests/measure/measure_scene_scale

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "accel/gpu_traversal.h"
#include "accel/registry.h"
#include "render/cpu_renderer.h"
#include "render/gpu_renderer.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"
#include "tests/gl_test_support.h"
#include "tests/registry_helpers.h"

namespace {

using namespace passtrace;

std::vector<HitRecord> primaryHits(const Scene& scene, int renderer, const std::string& accel, int size) {
  AccelBuildConfig build;
  build.gsTries = 1;
  if (renderer == 2) {
    const auto traversal = makeStreamStructure(accel, scene.triangles, GpuTraversalConfig{build, 20});
    GpuRenderer gpu(scene, *traversal, size, size);
    return gpu.render(scene.camera, 1, true).primaryHits;
  }
  const auto cpuAccel = makeCpuStructure(resolveStructure(accel, RendererId(renderer)), scene.triangles, build);
  CpuRenderer cpu(scene, *cpuAccel, 0);
  return cpu.render(scene.camera, size, size, 1, true).primaryHits;
}

}  // namespace

int main() {
  const std::filesystem::path bunny = "/usr/share/glmark2/models/bunny.obj";
  if (!std::filesystem::exists(bunny)) {
    std::fprintf(stderr, "no bunny at %s (glmark2-data)\n", bunny.c_str());
    return 1;
  }
  test::glContext();
  const Scene unit = loadObj(bunny);
  const int size = 32;
  const double scales[] = {1e-30, 1e-20, 1e-10, 1e10, 1e18, 1e20, 1e30};
  std::printf("| renderer | structure |");
  for (double s : scales) std::printf(" %g raw | %g rescaled |", s, s);
  std::printf("\n");
  for (const auto& [renderer, accel] : testing_registry::everyStructureRun()) {
    if (accel.find("split") != std::string::npos) continue;
    Scene reference = unit;
    reference.camera = framedCamera(reference.bounds());
    const std::vector<HitRecord> expected = primaryHits(reference, renderer, accel, size);
    std::printf("| %d | %s |", renderer, accel.c_str());
    for (double s : scales) {
      Scene raw = unit;
      for (Triangle& t : raw.triangles) t = {t.v0 * float(s), t.v1 * float(s), t.v2 * float(s)};
      raw.camera = framedCamera(raw.bounds());
      raw.light = framedLight(raw.bounds());
      Scene rescaled = raw;
      normalizeSceneScale(rescaled);
      for (const Scene* scene : {&raw, &rescaled}) {
        std::vector<HitRecord> got;
        try {
          got = primaryHits(*scene, renderer, accel, size);
        } catch (const std::exception& e) {
          std::printf(" error: %s |", e.what());
          continue;
        }
        int wrong = 0;
        for (size_t i = 0; i < got.size(); ++i) {
          const double t = std::ldexp(double(got[i].t), -scene->scaleExponent) / s;
          const bool same = got[i].id == expected[i].id ||
                            (got[i].id != kNoHit && expected[i].id != kNoHit && std::abs(t - expected[i].t) <= 1e-4 * expected[i].t);
          wrong += !same || (got[i].id != kNoHit && !(std::abs(t - expected[i].t) <= 1e-4 * expected[i].t));
        }
        std::printf(" %d |", wrong);
      }
      std::fflush(stdout);
    }
    std::printf("\n");
  }
  return 0;
}
