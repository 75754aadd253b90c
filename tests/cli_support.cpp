#include "tests/cli_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "accel/brute_force.h"
#include "render/camera.h"
#include "render/image_output.h"

namespace fs = std::filesystem;

namespace passtrace::test {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double litFraction(const std::string& imageFile) {
  int width = 0, height = 0;
  const std::vector<float> rgb = readImage(imageFile, width, height);
  size_t lit = 0;
  for (size_t p = 0; p + 2 < rgb.size(); p += 3)
    lit += std::any_of(rgb.begin() + long(p), rgb.begin() + long(p) + 3, [](float c) { return c > 0.2f; }) ? 1 : 0;
  return width * height == 0 ? 0.0 : double(lit) / double(size_t(width) * size_t(height));
}

std::string passtraceBinary() {
  const char* chosen = std::getenv("PASSTRACE_TEST_BINARY");
  return chosen && *chosen ? chosen : PASSTRACE_BINARY;
}

void CliTest::SetUp() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  std::replace(name.begin(), name.end(), '/', '_');  // parametrised tests: one directory, not a tree
  dir_ = fs::temp_directory_path() / ("passtrace_cli_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir_);
  fs::create_directories(dir_);
}

void CliTest::TearDown() { fs::remove_all(dir_); }

RunResult CliTest::run(const std::string& args, const std::string& env) {
  const std::string cmd = env + " " + passtraceBinary() + " " + args + " > " + (dir_ / "stdout").string() + " 2> " +
                          (dir_ / "stderr").string() + " < /dev/null";
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(dir_ / "stdout"), slurp(dir_ / "stderr")};
}

std::vector<std::string> CliTest::outputs() const {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_))
    if (!e.is_directory() && e.path().filename() != "stdout" && e.path().filename() != "stderr" && e.path().filename() != "bad.obj")
      names.push_back(e.path().filename().string());
  return names;
}

void CliTest::expectOneLineError(const RunResult& r, const std::string& mention) {
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.err.rfind("passtrace: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(mention), std::string::npos) << "expected '" << mention << "' in: " << r.err;
  EXPECT_TRUE(outputs().empty()) << "an output was left behind: " << outputs().front();
}

std::vector<Hit> bruteForceHits(const Scene& scene, int width, int height) {
  const CameraBasis basis = makeCameraBasis(scene.camera, width, height);
  std::vector<Hit> hits(size_t(width) * size_t(height));
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      Hit& h = hits[size_t(py) * size_t(width) + size_t(px)];
      h = intersectBruteForce(scene.triangles, primaryRay(basis, px, py), false);
      h.t = std::ldexp(h.t, -scene.scaleExponent);  // the file's units, exactly
    }
  return hits;
}

void expectHitsMatch(const std::string& file, const std::vector<Hit>& expectedHits, int width, int height,
                     double minFoundFraction, int allowedMismatches) {
  int w = 0, h = 0;
  const std::vector<HitRecord> hits = readHitBuffer(file, w, h);
  ASSERT_EQ(w, width);
  ASSERT_EQ(h, height);
  ASSERT_EQ(expectedHits.size(), hits.size());
  int found = 0, mismatches = 0;
  for (size_t i = 0; i < hits.size(); ++i) {
    const HitRecord& got = hits[i];
    const Hit& expected = expectedHits[i];
    found += expected.found();
    if (got.id == expected.id) {
      if (expected.found()) EXPECT_NEAR(got.t, expected.t, 1e-5f * expected.t);
      else EXPECT_EQ(got.t, kInfinity);
      continue;
    }
    // Two triangles met at the same t (a shared edge or vertex).
    const bool tie = expected.found() && got.id != kNoHit && std::abs(got.t - expected.t) <= 1e-5f * expected.t;
    if (!tie) ++mismatches;
  }
  EXPECT_LE(mismatches, allowedMismatches);
  EXPECT_GE(found, minFoundFraction * w * h);
  if (minFoundFraction > 0) {
    EXPECT_GT(found, 0);
  }
}

void expectHitsMatchBruteForce(const std::string& file, const Scene& scene, int width, int height,
                               double minFoundFraction, int allowedMismatches) {
  expectHitsMatch(file, bruteForceHits(scene, width, height), width, height, minFoundFraction, allowedMismatches);
}

}  // namespace passtrace::test
