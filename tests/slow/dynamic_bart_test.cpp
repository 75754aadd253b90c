// --dynamic on BART Robots (62,490 of its 71,708 triangles move): 10 frames
// (30 with PASSTRACE_FULL_MATRIX=1: 136 s of one core) with each strategy on
// the CPU and the GPU stream renderer, every frame's --hits buffer equal to
// brute force on that frame's geometry (computed once per frame and held
// against all six runs). Skipped without ../shared.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "accel/brute_force.h"
#include "render/camera.h"
#include "render/image_output.h"
#include "scenes/scene_registry.h"
#include "tests/bart_dir.h"
#include "tests/cli_support.h"
#include "tests/registry_helpers.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::slurp;
using Cli = test::CliTest;

constexpr int kSize = 24;
int frameCount() { return testing_registry::fullMatrix() ? 30 : 10; }

std::string numbered(const std::string& stem, int k) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%04d.exr", stem.c_str(), k);
  return name;
}

// The hit buffers' stem of a run: "h1merge".
std::string stemOf(int renderer, const std::string& strategy) {
  std::string stem(1, 'h');
  stem += char('0' + renderer);
  return stem.append(strategy);
}

// Brute force's primary hits on the scene's view, in the file's units (two threads).
std::vector<Hit> bruteHits(const Scene& scene) {
  const CameraBasis basis = makeCameraBasis(scene.camera, kSize, kSize);
  std::vector<Hit> hits(size_t(kSize) * kSize);
  auto rows = [&](int from, int to) {
    for (int py = from; py < to; ++py)
      for (int px = 0; px < kSize; ++px) {
        Hit h = intersectBruteForce(scene.triangles, primaryRay(basis, px, py), false);
        h.t = std::ldexp(h.t, -scene.scaleExponent);
        hits[size_t(py) * kSize + px] = h;
      }
  };
  std::thread half(rows, 0, kSize / 2);
  rows(kSize / 2, kSize);
  half.join();
  return hits;
}

// Hits equal, or another triangle at the same t (as expectHitsMatchBruteForce).
int mismatches(const std::string& file, const std::vector<Hit>& expected) {
  int w = 0, h = 0;
  const std::vector<HitRecord> got = readHitBuffer(file, w, h);
  if (w != kSize || h != kSize) return kSize * kSize;
  int bad = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    const Hit& e = expected[i];
    if (got[i].id == e.id && (!e.found() || std::abs(got[i].t - e.t) <= 1e-5f * e.t)) continue;
    const bool tie = e.found() && got[i].id != kNoHit && std::abs(got[i].t - e.t) <= 1e-5f * e.t;
    bad += tie ? 0 : 1;
  }
  return bad;
}

TEST_F(Cli, DynamicStrategiesOverBartRobots) {
  const fs::path bart = test::bartDir();
  if (bart.empty() || !fs::exists(bart / "robots")) GTEST_SKIP() << "BART scenes not found; set PASSTRACE_BART_DIR";
  const std::vector<std::pair<int, std::string>> runs = {
      {1, "rebuild"}, {1, "two-trees"}, {1, "merge"}, {2, "rebuild"}, {2, "two-trees"}, {2, "merge"}};
  const int frames = frameCount();
  std::vector<float> times;
  for (const auto& [renderer, strategy] : runs) {
    const std::string stem = stemOf(renderer, strategy);
    const auto r = run("-s robots --bart-dir " + bart.string() + " -r " + std::to_string(renderer) +
                       " -a kd-restart -w " + std::to_string(kSize) + " -b 1 --frames " + std::to_string(frames) +
                       " --dynamic " + strategy + " -o " + path("r.png") + " --hits " + path(stem + ".exr") +
                       " --json " + path(stem + ".json"));
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(slurp(path(stem + ".json")));
    ASSERT_EQ(j["sequence"].size(), size_t(frames));
    if (times.empty())
      for (const auto& f : j["sequence"]) times.push_back(f["time"].get<float>());
  }
  SceneOptions options;
  options.bartDir = bart;
  for (int k = 0; k < frames; ++k) {
    options.time = times[size_t(k)];
    const std::vector<Hit> expected = bruteHits(loadScene("robots", options));
    for (const auto& [renderer, strategy] : runs)
      EXPECT_EQ(mismatches(path(numbered(stemOf(renderer, strategy), k)), expected), 0)
          << "-r " << renderer << " --dynamic " << strategy << ", frame " << k;
  }
}

}  // namespace
}  // namespace passtrace
