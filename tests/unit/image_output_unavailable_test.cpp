// The image output of a build without OpenImageIO (-DPASSTRACE_IMAGE_OUTPUT=OFF,
// render/image_output_unavailable.cpp): every image or hit-buffer call is the
// one-line error the command line prints, and nothing is written. CI builds
// with OpenImageIO, so this binary compiles the stand-in on its own.
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "render/image_output.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

void expectUnavailable(const fs::path& path, const std::function<void()>& call) {
  try {
    call();
    ADD_FAILURE() << path << ": no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              path.string() + ": this passtrace was built without OpenImageIO (PASSTRACE_IMAGE_OUTPUT=OFF): no image files");
  }
  EXPECT_FALSE(fs::exists(path)) << path;
}

TEST(ImageOutputUnavailable, EveryCallIsAOneLineErrorAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path();
  const fs::path png = dir / "passtrace_no_oiio.png", exr = dir / "passtrace_no_oiio.exr";
  fs::remove(png);
  fs::remove(exr);
  int width = 0, height = 0;
  expectUnavailable(png, [&] { checkImageFormat(png); });
  expectUnavailable(png, [&] { encodeImage(png, 1, 1, {0.0f, 0.0f, 0.0f}); });
  expectUnavailable(exr, [&] { encodeHitBuffer(exr, 1, 1, {HitRecord{1.0f, 0.0f, 0.0f, 0u}}); });
  expectUnavailable(exr, [&] { readHitBuffer(exr, width, height); });
  expectUnavailable(exr, [&] { encodeConeHitBuffer(exr, 1, 1, {ConeHitRecord{}}); });
  expectUnavailable(exr, [&] { readConeHitBuffer(exr, width, height); });
}

}  // namespace
}  // namespace passtrace
