// passtrace under `mpirun -np 2` (issue 40): one frame's rows, the angles of
// -n and a --frames sequence divided between two ranks write the same bytes
// (images, hit buffers, heat maps) as one process, and the same JSON apart
// from timings, "ranks" and "rank_runs"; an error on one rank is one line,
// exit 1, nothing written and no hang. Skipped without Open MPI's mpirun or
// when passtrace was built without MPI.

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli_support.h"

namespace passtrace {
namespace {

using test::RunResult;
using test::slurp;

// Timings differ from run to run; everything else must not.
const std::set<std::string> kTimingKeys = {"build_ms", "frame_ms", "mrays_per_s", "total_ms", "static_build_ms",
                                           "trace_ms", "rank_runs", "ranks"};

// The JSON without its timings, for comparing runs.
nlohmann::json withoutTimings(nlohmann::json j) {
  if (j.is_object()) {
    for (const std::string& key : kTimingKeys) j.erase(key);
    for (auto& [key, value] : j.items()) value = withoutTimings(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = withoutTimings(value);
  }
  return j;
}

class MpiCli : public test::CliTest {
 protected:
  void SetUp() override {
#ifndef PASSTRACE_TEST_MPI
    GTEST_SKIP() << "passtrace was built without MPI (PASSTRACE_MPI, or no MPI found at configure time)";
#endif
    if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
      GTEST_SKIP() << "no mpirun on PATH (Open MPI: bash scripts/setup.sh --tests installs it)";
    test::CliTest::SetUp();
  }
  // `mpirun -np N passtrace ARGS`; -q leaves only passtrace's own lines on
  // stderr. Root may launch only when it says so (these machines run as root).
  RunResult runRanks(int n, const std::string& args) {
    return run(args, std::string(kLaunch) + " -np " + std::to_string(n));
  }
  static constexpr const char* kLaunch = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -q";
  // A shell command line, its streams captured as run() captures passtrace's.
  RunResult shell(const std::string& command) {
    const int raw = std::system((command + " > " + path("stdout") + " 2> " + path("stderr") + " < /dev/null").c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(path("stdout")), slurp(path("stderr"))};
  }
  // The same run in one process and in two ranks, `{}` in ARGS standing for
  // the output folder's prefix: every file the one writes, the two write byte
  // for byte; the JSONs agree but for timings; "ranks" says 2.
  void expectSameOutputs(const std::string& args, const std::vector<std::string>& files) {
    const auto with = [&](const std::string& prefix) {
      std::string a = args;
      for (size_t at; (at = a.find("{}")) != std::string::npos;) a.replace(at, 2, path(prefix));
      return a;
    };
    const RunResult one = run(with("one_"));
    ASSERT_EQ(one.status, 0) << one.err;
    const RunResult two = runRanks(2, with("two_"));
    ASSERT_EQ(two.status, 0) << two.err;
    for (const std::string& f : files) {
      const std::string a = slurp(path("one_" + f)), b = slurp(path("two_" + f));
      EXPECT_FALSE(a.empty()) << f;
      EXPECT_TRUE(a == b) << f << " differs between one process and two ranks: " << args;
    }
    const nlohmann::json j1 = nlohmann::json::parse(slurp(path("one_j.json")));
    const nlohmann::json j2 = nlohmann::json::parse(slurp(path("two_j.json")));
    EXPECT_EQ(j1["ranks"], 1);
    EXPECT_EQ(j2["ranks"], 2);
    ASSERT_EQ(j2["rank_runs"].size(), 2u);
    for (int r = 0; r < 2; ++r) {
      EXPECT_EQ(j2["rank_runs"][r]["rank"], r);
      EXPECT_FALSE(j2["rank_runs"][r]["host"].get<std::string>().empty());
      EXPECT_GT(j2["rank_runs"][r]["share"].get<int>(), 0) << "rank " << r << " did nothing: " << args;
    }
    EXPECT_EQ(withoutTimings(j1), withoutTimings(j2)) << args;
  }
};

// One frame: the ranks trace interleaved bands of rows, rank 0 puts them together.
TEST_F(MpiCli, OneFrameDividedByRowsWritesOneProcesssBytes) {
  const std::string outs = " --width 96 --height 80 -o {}i.png --hits {}h.exr --heatmap {}m.png --json {}j.json";
  const std::vector<std::string> files = {"i.png", "h.exr", "m.png"};
  for (const std::string row : {"-r 1 -a bvh8 -b 2", "-r 2 -a kk-bvh -b 2", "-r 1 -a kd-tree --shading ao",
                                "-r 2 -a gs-bvh --shading ao --stage compute", "-r 2 -a bvh-octant-fused -b 1",
                                "-r 1 -a bvh8-packet --shading whitted"})
    expectSameOutputs("-s bunny " + row + outs, files);
}

// A batch tracer's counts depend on the rays traced together (the registry's
// cpuRayGrouping): its single frame stays whole on rank 0. (Its counters also
// follow the CPUs a process may use, which mpirun binds: only the image and
// hits are compared.)
TEST_F(MpiCli, ABatchTracersFrameStaysWholeOnRankZero) {
  const std::string args = " -s bunny -r 1 -a dacrt -b 2 --width 64 --height 48";
  ASSERT_EQ(run(args + " -o " + path("one.png") + " --hits " + path("one.exr")).status, 0);
  const RunResult two = runRanks(2, args + " -o " + path("two.png") + " --hits " + path("two.exr") + " --json " +
                                        path("two.json"));
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_TRUE(slurp(path("one.png")) == slurp(path("two.png")));
  EXPECT_TRUE(slurp(path("one.exr")) == slurp(path("two.exr")));
  const nlohmann::json j = nlohmann::json::parse(slurp(path("two.json")));
  EXPECT_EQ(j["rank_runs"][0]["share"], 1);
  EXPECT_EQ(j["rank_runs"][1]["share"], 0);
}

// -n 4 -p: the angles dealt out in turn; every angle's image and the sums.
TEST_F(MpiCli, AnglesDividedWriteOneProcesssImages) {
  expectSameOutputs("-s bunny -r 1 -a bvh8 -n 4 -p -w 64 -o {}i.png --json {}j.json",
                    {"i.png", "i_0.png", "i_1.png", "i_2.png", "i_3.png"});
  expectSameOutputs("-s cornell -r 2 -a kd-restart -n 3 -w 32 -o {}i.png --hits {}h.exr --json {}j.json",
                    {"i.png", "h.exr"});
}

// --frames: the frames dealt out in turn, rebuilt per frame or from the static tree.
TEST_F(MpiCli, SequenceFramesDividedWriteOneProcesssFiles) {
  const std::string scene = std::string(PASSTRACE_TEST_DATA) + "/gltf/dynamic.gltf";
  std::vector<std::string> files;
  for (int f = 0; f < 5; ++f)
    for (const char* name : {"f_000", "h_000"}) files.push_back(name + std::to_string(f) + (name[0] == 'f' ? ".png" : ".exr"));
  expectSameOutputs("-s " + scene + " -r 1 -a kd-tree --frames 5 -w 48 -o {}f.png --hits {}h.exr --json {}j.json", files);
  expectSameOutputs("-s " + scene + " -r 2 -a kd-restart --dynamic merge --frames 5 -w 48 -o {}f.png --hits {}h.exr "
                    "--json {}j.json", files);
}

// A bad scene on rank 1 only: the other rank does not wait for it forever;
// one line naming the rank and the file's line, exit 1, nothing written.
TEST_F(MpiCli, AnErrorOnOneRankEndsEveryRankWithOneLine) {
  {
    std::ofstream bad(path("bad.obj"));
    bad << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n";
  }
  const std::string good = test::passtraceBinary() + " -s bunny -r 1 -w 64 -o " + path("e.png");
  const std::string broken = test::passtraceBinary() + " -s " + path("bad.obj") + " -r 1 -w 64 -o " + path("e.png");
  const RunResult r = shell(std::string("timeout 120 env ") + kLaunch + " -np 2 sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; "
                            "then exec " + broken + "; else exec " + good + "; fi'");
  EXPECT_NE(r.status, 124) << "the ranks hung";
  expectOneLineError(r, "rank 1: " + path("bad.obj") + ":4");
  // The same on every rank (a file that cannot be written): still one line.
  expectOneLineError(runRanks(2, "-s cornell -r 1 -w 16 -o " + path("missing/x.png")), "rank 0");
  // A frame with fewer rows than ranks to divide them among.
  expectOneLineError(runRanks(2, "-s cornell -r 1 --width 8 --height 1 -o " + path("x.png")), "--height 1");
}

}  // namespace
}  // namespace passtrace
