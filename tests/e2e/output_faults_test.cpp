// Nothing lost, nothing half-written: a disk that fills part-way through a
// run leaves none of its outputs and no temporary file, with a one-line error
// and exit 1, for every kind of output (render/output_files.h). The full disk
// is the preloaded shim tests/fault/fail_writes.c (every write to a regular
// file fails after N bytes) and, where the test may mount one, a small tmpfs.
// Devices and pipes: /dev/full fails the run, /dev/null and a pipe work.

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;
using test::slurp;

const std::string kGltf = std::string(PASSTRACE_TEST_DATA) + "/gltf/";

// A run and the files it writes, in the order it writes them (NAME: in the
// test's directory).
struct OutputRun {
  std::string name, args;
  std::vector<std::string> files;
};

// Test names show the run's name, not its bytes.
void PrintTo(const OutputRun& run, std::ostream* os) { *os << run.name; }

// {} in args stands for the test's directory.
const OutputRun kRuns[] = {
    {"PngHitsJson", "-s cornell -r 1 -w 16 -b 1 -o {}/img.png --hits {}/h.exr --json {}/j.json",
     {"img.png", "h.exr", "j.json"}},
    {"ExrHeatmapJson", "-s cornell -r 1 -w 16 -b 1 -o {}/img.exr --heatmap {}/heat.png --json {}/j.json",
     {"img.exr", "heat.png", "j.json"}},
    {"AngleDumps", "-s cornell -r 1 -w 16 -b 1 -n 3 -p -o {}/v.png", {"v_0.png", "v_1.png", "v_2.png", "v.png"}},
    {"FrameSequence",
     "-s " + kGltf + "animated.gltf -r 1 -w 16 -b 1 --frames 2 -o {}/f.png --hits {}/h.exr --json {}/j.json",
     {"f_0000.png", "h_0000.exr", "f_0001.png", "h_0001.exr", "j.json"}},
    {"ConeHits", "-s cornell -r 1 -w 16 -a kd-tree --cone 1 --cone-hits {}/c.exr --heatmap {}/heat.png --json {}/j.json",
     {"c.exr", "heat.png", "j.json"}},
    {"ExportObj", "-s cornell --export {}/x.obj", {"x.mtl", "x.obj"}},
    {"ExportGltf", "-s cornell --export {}/x.gltf", {"x.gltf"}},
    {"ExportGlb", "-s cornell --export {}/x.glb", {"x.glb"}},
    {"ListJson", "--list --json {}/list.json", {"list.json"}},
};

std::string expand(std::string args, const fs::path& dir) {
  for (size_t at; (at = args.find("{}")) != std::string::npos;) args.replace(at, 2, dir.string());
  return args;
}

// Appended to any LD_PRELOAD already set (scripts/sanitize.sh sets one).
std::string failingAfter(long long bytes) {
  return std::string("LD_PRELOAD=\"${LD_PRELOAD:+$LD_PRELOAD:}") + PASSTRACE_FAIL_WRITES + "\" PASSTRACE_FAIL_WRITES_AFTER=" +
         std::to_string(bytes);
}

class OutputFaults : public test::CliTest, public ::testing::WithParamInterface<OutputRun> {
 protected:
  void SetUp() override {
    test::CliTest::SetUp();
#ifdef __SANITIZE_ADDRESS__
    // ASan refuses a preloaded library ahead of its runtime unless told not to.
    const char* options = std::getenv("ASAN_OPTIONS");
    if (!options || !std::strstr(options, "verify_asan_link_order=0"))
      GTEST_SKIP() << "the fault shim needs ASAN_OPTIONS=verify_asan_link_order=0 under AddressSanitizer "
                      "(scripts/sanitize.sh sets it)";
#endif
  }
};

TEST_P(OutputFaults, ADiskThatFillsLeavesNoOutputAndNoTemporaryFile) {
  const OutputRun& run = GetParam();
  const std::string args = expand(run.args, dir_);
  // The whole run first, through the shim with room to spare: every file, and
  // their sizes to aim the faults at.
  const test::RunResult ok = this->run(args, failingAfter(1LL << 40));
  ASSERT_EQ(ok.status, 0) << ok.err;
  std::vector<long long> sizes;
  for (const std::string& file : run.files) {
    ASSERT_TRUE(fs::is_regular_file(dir_ / file)) << file;
    sizes.push_back(static_cast<long long>(fs::file_size(dir_ / file)));
    fs::remove(dir_ / file);
  }
  ASSERT_TRUE(outputs().empty()) << "an unexpected file: " << outputs().front();
  // The disk full from the start, then half-way through each file in turn
  // (the second, third ... with every earlier one complete).
  long long before = 0;
  std::vector<std::pair<long long, std::string>> faults{{0, run.files.front()}};
  for (size_t i = 0; i < sizes.size(); ++i) {
    faults.push_back({before + sizes[i] / 2, run.files[i]});
    before += sizes[i];
  }
  for (const auto& [after, file] : faults) {
    SCOPED_TRACE("full after " + std::to_string(after) + " bytes, in " + file);
    const test::RunResult r = this->run(args, failingAfter(after));
    EXPECT_EQ(r.status, 1);
    expectOneLineError(r, file + ": write failed: No space left on device");
  }
}

INSTANTIATE_TEST_SUITE_P(EveryOutputKind, OutputFaults, ::testing::ValuesIn(kRuns),
                         [](const auto& info) { return info.param.name; });

class OutputTargets : public test::CliTest {};

// The case on a real file system: the image fits, the hit buffer
// does not. A tmpfs of its own needs a mount namespace (root, or user
// namespaces); without one the shim above covers the same paths.
TEST_F(OutputTargets, AFullTmpfsLeavesNothing) {
  const std::string args = "-s cornell -r 1 -w 64 -b 1 -o {}/img.exr --hits {}/h.exr --json {}/j.json";
  ASSERT_EQ(run(expand(args, dir_)).status, 0);
  const long long image = static_cast<long long>(fs::file_size(dir_ / "img.exr"));
  const long long hits = static_cast<long long>(fs::file_size(dir_ / "h.exr"));
  for (const char* f : {"img.exr", "h.exr", "j.json"}) fs::remove(dir_ / f);
  const long long page = 4096;
  const long long size = (image + page - 1) / page * page + hits / 2 / page * page;
  ASSERT_GT(hits / 2, page) << "the hit buffer must be large enough to fill the file system part-way";
  const fs::path mount = dir_ / "fs";
  fs::create_directory(mount);
  const std::string inside = "mount -t tmpfs -o size=" + std::to_string(size) + " tmpfs " + mount.string() +
                             " 2>/dev/null || exit 77; " + test::passtraceBinary() + " " + expand(args, mount) + " > " +
                             path("stdout") + " 2> " + path("stderr") + " < /dev/null; echo $? > " +
                             path("status") + "; ls -A " + mount.string() + " > " + path("listing");
  int raw = -1;
  for (const char* unshare : {"unshare -m", "unshare -rm"}) {
    raw = std::system((std::string(unshare) + " sh -c '" + inside + "' 2>/dev/null").c_str());
    if (WIFEXITED(raw) && WEXITSTATUS(raw) == 0) break;
  }
  if (!(WIFEXITED(raw) && WEXITSTATUS(raw) == 0))
    GTEST_SKIP() << "cannot mount a tmpfs here (unshare -m / -rm refused): the fault shim covers this";
  EXPECT_EQ(std::stoi(slurp(path("status"))), 1);
  const std::string err = slurp(path("stderr"));
  EXPECT_EQ(err.rfind("passtrace: error: " + (mount / "h.exr").string() + ": write failed: No space left on device", 0), 0u)
      << err;
  EXPECT_EQ(slurp(path("listing")), "") << "left on the full file system";
}

TEST_F(OutputTargets, ADeviceThatRefusesTheReportFailsTheRun) {
  const test::RunResult r = run("-s cornell -r 1 -w 16 -b 1 -o " + path("img.png") + " --json /dev/full");
  EXPECT_EQ(r.status, 1);
  expectOneLineError(r, "/dev/full: write failed: No space left on device");
  EXPECT_TRUE(fs::is_character_file("/dev/full")) << "the device was replaced";
}

TEST_F(OutputTargets, DevicesAndPipesAreWrittenInto) {
  const test::RunResult devNull = run("-s cornell -r 1 -w 16 -b 1 -o " + path("img.png") + " --json /dev/null");
  EXPECT_EQ(devNull.status, 0) << devNull.err;
  EXPECT_TRUE(fs::is_regular_file(path("img.png")));
  EXPECT_TRUE(fs::is_character_file("/dev/null")) << "the device was replaced";
  // --json to a pipe: the report comes through it whole.
  const std::string cmd = test::passtraceBinary() + " -q -s cornell -r 1 -w 16 -b 1 --json /dev/stdout | cat > " +
                          path("piped.json");
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(path("piped.json")))["scene"], "cornell");
}

}  // namespace
}  // namespace passtrace
