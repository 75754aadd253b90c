// Images and hit buffers encoded with OpenImageIO and written as a run writes them.

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "render/image_output.h"
#include "render/output_files.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kMiss = 0xFFFFFFFFu;

// A fresh directory for the test's files, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* test = testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("passtrace-image-" + std::string(test->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  // What the directory holds, temporary files included.
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.insert(entry.path().filename().string());
    return names;
  }

 private:
  fs::path path_;
};

// The message of the std::runtime_error that write throws, or a test failure.
template <class Write>
std::string errorOf(Write&& write) {
  try {
    write();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error thrown";
  return {};
}

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// One file written as a run writes it: encoded, then put in place.
void commitOne(const fs::path& path, const std::string& bytes) {
  OutputFiles outputs;
  outputs.write(path, bytes);
  outputs.commitAll();
}
void writeImage(const fs::path& path, int width, int height, const std::vector<float>& rgb) {
  commitOne(path, encodeImage(path, width, height, rgb));
}
void writeHitBuffer(const fs::path& path, int width, int height, const std::vector<HitRecord>& hits) {
  commitOne(path, encodeHitBuffer(path, width, height, hits));
}

TEST(ImageOutput, PngRoundTripClampsWithoutGamma) {
  const TempDir dir;
  const int width = 4, height = 3;
  std::vector<float> rgb(width * height * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(i) / 255.0f;
  rgb[0] = 2.0f;  // the top-left pixel, clamped to 1, 0, 0
  rgb[1] = -1.0f;
  rgb[2] = std::nanf("");
  const fs::path path = dir / "out.png";
  writeImage(path, width, height, rgb);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"out.png"});

  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->format_name(), std::string("png"));
  EXPECT_EQ(in->spec().width, width);
  EXPECT_EQ(in->spec().height, height);
  EXPECT_EQ(in->spec().nchannels, 3);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> pixels(rgb.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  EXPECT_EQ(pixels[0], 255);
  EXPECT_EQ(pixels[1], 0);
  EXPECT_EQ(pixels[2], 0);
  for (std::size_t i = 3; i < pixels.size(); ++i) EXPECT_EQ(pixels[i], i) << i;
}

TEST(ImageOutput, ExrKeepsFloats) {
  const TempDir dir;
  const std::vector<float> rgb = {2.5f, -1.0f, 0.125f, 1e6f, 0.0f, 1.0f};
  const fs::path path = dir / "out.exr";
  writeImage(path, 2, 1, rgb);
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
  std::vector<float> back(rgb.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, back.data()));
  EXPECT_EQ(back, rgb);
}

TEST(ImageOutput, ReplacesAnExistingFile) {
  const TempDir dir;
  const fs::path path = dir / "out.png";
  writeImage(path, 1, 1, {0.0f, 0.0f, 0.0f});
  writeImage(path, 1, 1, {1.0f, 1.0f, 1.0f});
  EXPECT_EQ(dir.entries(), std::set<std::string>{"out.png"});
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in);
  uint8_t pixel[3] = {};
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixel));
  EXPECT_EQ(pixel[0], 255);
}

TEST(ImageOutput, HitBufferRoundTrip) {
  const TempDir dir;
  const std::vector<HitRecord> hits = {
      {kInf, 0.0f, 0.0f, kMiss},          {1.5f, 0.25f, 0.5f, 0u},
      {2.0f, 0.1f, 0.2f, 16777217u},      {1e-7f, 1.0f, 0.0f, 0xFFFFFFFEu},
      {123.456f, 0.333f, 0.666f, 69665u}, {kInf, 0.0f, 0.0f, kMiss},
  };
  const fs::path path = dir / "hits.exr";
  writeHitBuffer(path, 3, 2, hits);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"hits.exr"});

  // The file itself: exactly these channels, in these types.
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->format_name(), std::string("openexr"));
  const OIIO::ImageSpec& spec = in->spec();
  ASSERT_EQ(spec.nchannels, 4);
  const std::set<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  EXPECT_EQ(names, (std::set<std::string>{"t", "u", "v", "id"}));
  for (const char* name : {"t", "u", "v"})
    EXPECT_EQ(spec.channelformat(spec.channelindex(name)), OIIO::TypeDesc::FLOAT) << name;
  EXPECT_EQ(spec.channelformat(spec.channelindex("id")), OIIO::TypeDesc::UINT32);
  in.reset();

  int width = 0, height = 0;
  const std::vector<HitRecord> back = readHitBuffer(path, width, height);
  EXPECT_EQ(width, 3);
  EXPECT_EQ(height, 2);
  ASSERT_EQ(back.size(), hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    EXPECT_EQ(back[i].t, hits[i].t) << i;
    EXPECT_EQ(back[i].u, hits[i].u) << i;
    EXPECT_EQ(back[i].v, hits[i].v) << i;
    EXPECT_EQ(back[i].id, hits[i].id) << i;
  }
}

TEST(ImageOutput, HitBufferMustBeExr) {
  const TempDir dir;
  const fs::path path = dir / "hits.png";
  const std::string message = errorOf([&] { writeHitBuffer(path, 1, 1, {{kInf, 0, 0, kMiss}}); });
  EXPECT_TRUE(startsWith(message, path.string() + ": ")) << message;
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageOutput, ReadHitBufferChecksChannels) {
  const TempDir dir;
  const fs::path rgb = dir / "rgb.exr";
  writeImage(rgb, 1, 1, {0.0f, 0.0f, 0.0f});
  int width = 0, height = 0;
  EXPECT_EQ(errorOf([&] { readHitBuffer(rgb, width, height); }), rgb.string() + ": no channel 't'");

  // All-float channels: an id above 2^24 could not be trusted.
  const fs::path floats = dir / "floats.exr";
  OIIO::ImageSpec spec(1, 1, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"t", "u", "v", "id"};
  auto out = OIIO::ImageOutput::create(floats.string());
  ASSERT_TRUE(out && out->open(floats.string(), spec));
  const float pixel[4] = {1.0f, 0.0f, 0.0f, 3.0f};
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixel) && out->close());
  EXPECT_EQ(errorOf([&] { readHitBuffer(floats, width, height); }),
            floats.string() + ": channel 'id' is float, expected uint32");

  const fs::path missing = dir / "missing.exr";
  EXPECT_TRUE(startsWith(errorOf([&] { readHitBuffer(missing, width, height); }), missing.string() + ": "));
}

TEST(ImageOutput, ChecksTheFormatBeforeRendering) {
  const TempDir dir;
  EXPECT_NO_THROW(checkImageFormat(dir / "out.png"));
  EXPECT_NO_THROW(checkImageFormat(dir / "out.EXR"));
  const fs::path unknown = dir / "out.unknownformat";
  EXPECT_TRUE(startsWith(errorOf([&] { checkImageFormat(unknown); }), unknown.string() + ": "));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageOutput, FailuresLeaveNothingBehind) {
  const TempDir dir;
  const std::vector<float> black(3, 0.0f);

  const fs::path noDirectory = dir / "missing" / "out.png";
  EXPECT_TRUE(startsWith(errorOf([&] { writeImage(noDirectory, 1, 1, black); }), noDirectory.string() + ": "));

  const fs::path unknown = dir / "out.unknownformat";
  EXPECT_TRUE(startsWith(errorOf([&] { writeImage(unknown, 1, 1, black); }), unknown.string() + ": "));

  // A writer that cannot write to memory could not report a full disk.
  const fs::path noMemoryWriter = dir / "out.sgi";
  EXPECT_NE(errorOf([&] { checkImageFormat(noMemoryWriter); }).find("cannot write to memory"), std::string::npos);

  const fs::path wrongSize = dir / "small.png";
  EXPECT_EQ(errorOf([&] { writeImage(wrongSize, 2, 2, black); }),
            wrongSize.string() + ": expected 12 values for 2x2, got 3");
  EXPECT_TRUE(dir.entries().empty());

  // The final name is taken by a directory: refused before anything is written.
  // fails, and the temporary file must go.
  const fs::path taken = dir / "taken.png";
  fs::create_directory(taken);
  EXPECT_TRUE(startsWith(errorOf([&] { writeImage(taken, 1, 1, black); }), taken.string() + ": is a directory"));
  EXPECT_EQ(dir.entries(), std::set<std::string>{"taken.png"});
  EXPECT_TRUE(fs::is_directory(taken));
}

TEST(ImageOutput, UnwritableDirectory) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write into read-only directories";
  const TempDir dir;
  fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
  const fs::path path = dir / "out.exr";
  EXPECT_TRUE(startsWith(errorOf([&] { writeImage(path, 1, 1, {0.0f, 0.0f, 0.0f}); }), path.string() + ": "));
  fs::permissions(dir.path(), fs::perms::owner_all);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace passtrace
