// A run's outputs (render/output_files.h): nothing appears before commitAll,
// everything at it; failures leave neither final names nor temporary files;
// devices and pipes are written into, not replaced. Full disks part-way
// through a run: tests/e2e/output_faults_test.cpp.

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "render/output_files.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

class OutputFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("passtrace-outputs-" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Every entry, hidden temporary files included.
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.insert(e.path().filename().string());
    return names;
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // The message of what `call` throws, checked to be one line.
  template <class Call>
  static std::string errorOf(Call&& call) {
    try {
      call();
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return {};
  }
  fs::path dir_;
};

TEST_F(OutputFilesTest, EveryFileAppearsAtCommitAndNotBefore) {
  OutputFiles outputs;
  outputs.write(dir_ / "a.json", "{}\n");
  outputs.write(dir_ / "b.png", std::string(10000, 'x'));
  EXPECT_FALSE(fs::exists(dir_ / "a.json"));
  EXPECT_FALSE(fs::exists(dir_ / "b.png"));
  outputs.commitAll();
  EXPECT_EQ(entries(), (std::set<std::string>{"a.json", "b.png"}));
  EXPECT_EQ(read(dir_ / "a.json"), "{}\n");
  EXPECT_EQ(read(dir_ / "b.png"), std::string(10000, 'x'));
}

TEST_F(OutputFilesTest, NoCommitLeavesNothingAndKeepsWhatWasThere) {
  std::ofstream(dir_ / "a.json") << "old";
  {
    OutputFiles outputs;
    outputs.write(dir_ / "a.json", "new");
    outputs.write(dir_ / "b.exr", "pixels");
  }
  EXPECT_EQ(entries(), std::set<std::string>{"a.json"});
  EXPECT_EQ(read(dir_ / "a.json"), "old");
}

TEST_F(OutputFilesTest, ADeviceThatRefusesFailsTheRunBeforeAnyFileAppears) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  {
    OutputFiles outputs;
    outputs.write(dir_ / "image.png", "pixels");
    outputs.write("/dev/full", "{}\n");
    EXPECT_EQ(errorOf([&] { outputs.commitAll(); }), "/dev/full: write failed: No space left on device");
    EXPECT_FALSE(fs::exists(dir_ / "image.png"));
  }  // the run's error unwinds past its outputs: the temporary file goes
  EXPECT_TRUE(entries().empty()) << *entries().begin();
}

TEST_F(OutputFilesTest, DevicesAndPipesAreWrittenIntoNotReplaced) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read(fifo); });
  OutputFiles outputs;
  outputs.write("/dev/null", "discarded");
  outputs.write(fifo, "through the pipe");
  outputs.write(dir_ / "a.txt", "a");
  outputs.commitAll();
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(entries(), (std::set<std::string>{"a.txt", "pipe"}));
}

TEST_F(OutputFilesTest, ASymbolicLinkIsFollowedNotReplaced) {
  fs::create_symlink("real.json", dir_ / "link.json");
  OutputFiles outputs;
  outputs.write(dir_ / "link.json", "through the link");
  outputs.commitAll();
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.json"));
  EXPECT_EQ(read(dir_ / "real.json"), "through the link");
  EXPECT_EQ(entries(), (std::set<std::string>{"link.json", "real.json"}));
}

TEST_F(OutputFilesTest, BadTargetsAreOneLineErrorsNamingTheFile) {
  OutputFiles outputs;
  const fs::path missing = dir_ / "missing" / "a.png";
  EXPECT_EQ(errorOf([&] { outputs.write(missing, "x"); }).rfind(missing.string() + ": ", 0), 0u);
  fs::create_directory(dir_ / "taken.png");
  EXPECT_EQ(errorOf([&] { outputs.write(dir_ / "taken.png", "x"); }), (dir_ / "taken.png").string() + ": is a directory");
  outputs.write(dir_ / "a.png", "x");
  EXPECT_EQ(errorOf([&] { outputs.write(dir_ / "." / "a.png", "y"); }),
            (dir_ / "." / "a.png").string() + ": named by two outputs of the run");
}

}  // namespace
}  // namespace passtrace
