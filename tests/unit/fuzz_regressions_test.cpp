// Every input the fuzz targets (tests/fuzz/) or hand-made probes of the same
// kind found crashing, hanging, exhausting memory or giving a bad message,
// kept in tests/data/fuzz_regressions/<target>/ and required to end cleanly
// now: a SceneError of one line naming the file (or a parse error of one
// line), or a successful load that keeps Scene's promises. The folders are
// copied to a scratch directory where each also holds `fifo` (a FIFO) and
// `adir` (a directory), the special files some inputs name; subfolders hold
// files that inputs include.

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"
#include "tests/fuzz/cli_input.h"
#include "tests/fuzz/scene_invariants.h"

namespace fs = std::filesystem;

namespace passtrace {
namespace {

const fs::path kRegressions = fs::path(PASSTRACE_TEST_DATA) / "fuzz_regressions";

// The files of one target's folder with the given extensions, in name order.
std::vector<fs::path> inputsIn(const fs::path& folder, std::initializer_list<const char*> extensions) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    for (const char* extension : extensions)
      if (entry.is_regular_file() && entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class FuzzRegressions : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("passtrace_fuzz_regressions_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::copy(kRegressions, dir_, fs::copy_options::recursive);
    for (const char* target : {"obj", "aff", "gltf", "ply"}) {
      fs::create_directories(dir_ / target / "adir");
      ASSERT_EQ(::mkfifo((dir_ / target / "fifo").c_str(), 0600), 0);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Loads one input; an empty result is a clean outcome.
  template <class Load>
  static std::string outcome(const fs::path& input, Load&& load) {
    try {
      return fuzz::sceneProblem(load(input));
    } catch (const SceneError& e) {
      const std::string problem = fuzz::errorProblem(e.what(), input.string());
      return problem.empty() ? "" : problem + ": " + e.what();
    }
  }

  fs::path dir_;
};

TEST_F(FuzzRegressions, ObjInputsEndCleanly) {
  for (const fs::path& input : inputsIn(dir_ / "obj", {".obj"}))
    EXPECT_EQ(outcome(input, [](const fs::path& p) { return loadScene(p.string()); }), "") << input;
}

TEST_F(FuzzRegressions, AffInputsEndCleanly) {
  for (const fs::path& input : inputsIn(dir_ / "aff", {".aff", ".nff"})) {
    // The animation time fuzz_aff derives from the input's length.
    const float time = static_cast<float>(fs::file_size(input) % 17) * 0.25f;
    SceneOptions options;
    options.time = time;
    EXPECT_EQ(outcome(input, [&](const fs::path& p) { return loadScene(p.string(), options); }), "") << input;
  }
}

TEST_F(FuzzRegressions, GltfInputsEndCleanly) {
  for (const fs::path& input : inputsIn(dir_ / "gltf", {".gltf", ".glb"}))
    EXPECT_EQ(outcome(input, [](const fs::path& p) { return loadScene(p.string()); }), "") << input;
}

TEST_F(FuzzRegressions, PlyInputsEndCleanly) {
  for (const fs::path& input : inputsIn(dir_ / "ply", {".ply"}))
    EXPECT_EQ(outcome(input, [](const fs::path& p) { return loadScene(p.string()); }), "") << input;
}

TEST_F(FuzzRegressions, CommandLinesEndCleanly) {
  for (const fs::path& input : inputsIn(kRegressions / "cli", {".args"})) {
    Options options;
    std::string problem;
    try {
      if (fuzz::parseWords(fuzz::splitArguments(slurp(input)), options) == 0) problem = fuzz::optionsProblem(options);
    } catch (const std::runtime_error& e) {
      if (std::string(e.what()).find('\n') != std::string::npos) problem = "error message spans lines";
    }
    EXPECT_EQ(problem, "") << input;
  }
}

}  // namespace
}  // namespace passtrace
