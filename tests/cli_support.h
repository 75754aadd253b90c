#pragma once
// Shared by the tests that run the passtrace binary: a fixture with a fresh
// temporary directory, running the command line and capturing its streams,
// the one-line error contract, and hit buffers checked against brute force.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/scene.h"

namespace passtrace::test {

struct RunResult {
  int status;
  std::string out, err;
};

std::string slurp(const std::filesystem::path& p);

// The passtrace program the tests run: $PASSTRACE_TEST_BINARY when set (the
// sanitized run points this build's tests at its instrumented program,
// scripts/sanitize.sh), else the one built beside them (PASSTRACE_BINARY).
std::string passtraceBinary();

// The fraction of an image's pixels with some channel above 0.2: how much of
// a render is lit (issue 34's measure of a readable image).
double litFraction(const std::string& imageFile);

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  // Runs `passtrace ARGS` (with environment assignments ENV) in the shell.
  RunResult run(const std::string& args, const std::string& env = "");
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Files in the directory other than the captured streams and bad.obj
  // (subdirectories, which may hold a test's inputs, are not listed).
  std::vector<std::string> outputs() const;
  // Non-zero exit, exactly one "passtrace: error: ..." line naming `mention`,
  // and no output file left behind.
  void expectOneLineError(const RunResult& r, const std::string& mention);

  std::filesystem::path dir_;
};

// The hit buffer FILE (width x height) against brute force on the scene's own
// view: the same triangle, or another one at the same t (a shared edge or a
// duplicate) within 1e-5 relative; t is read in the file's units
// (Scene::scaleExponent). At least minFoundFraction of the pixels must hit;
// at most allowedMismatches may differ otherwise.
void expectHitsMatchBruteForce(const std::string& file, const Scene& scene, int width, int height,
                               double minFoundFraction = 0.1, int allowedMismatches = 0);
inline void expectHitsMatchBruteForce(const std::string& file, const Scene& scene, int size) {
  expectHitsMatchBruteForce(file, scene, size, size);
}
// The same in two steps, for many runs on one scene: brute force's primary
// hits on the scene's own view (t in the file's units), computed once, and a
// hit buffer against them.
std::vector<Hit> bruteForceHits(const Scene& scene, int width, int height);
void expectHitsMatch(const std::string& file, const std::vector<Hit>& expected, int width, int height,
                     double minFoundFraction = 0.1, int allowedMismatches = 0);

}  // namespace passtrace::test
