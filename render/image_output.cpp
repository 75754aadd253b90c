#include "render/image_output.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "render/exr_io.h"
#include "render/oiio_module.h"
#include "scenes/file_extension.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& reason) {
  throw std::runtime_error(path.string() + ": " + reason);
}

bool isExr(const fs::path& path) { return lowerExtension(path) == ".exr"; }

void checkSize(const fs::path& path, int width, int height, std::size_t values, std::size_t perPixel) {
  if (width <= 0 || height <= 0)
    fail(path, "bad image size " + std::to_string(width) + "x" + std::to_string(height));
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * perPixel;
  if (values != expected)
    fail(path, "expected " + std::to_string(expected) + " values for " + std::to_string(width) + "x" +
                   std::to_string(height) + ", got " + std::to_string(values));
}

constexpr ExrChannel kRgbChannels[] = {{"R", false, 0}, {"G", false, 4}, {"B", false, 8}};
constexpr ExrChannel kHitChannels[] = {{"t", false, offsetof(HitRecord, t)},
                                       {"u", false, offsetof(HitRecord, u)},
                                       {"v", false, offsetof(HitRecord, v)},
                                       {"id", true, offsetof(HitRecord, id)}};
constexpr ExrChannel kConeHitChannels[] = {{"count", true, offsetof(ConeHitRecord, count)},
                                           {"id", true, offsetof(ConeHitRecord, id)},
                                           {"t", false, offsetof(ConeHitRecord, t)}};

template <class Pixel>
std::vector<Pixel> readPixels(const fs::path& path, std::span<const ExrChannel> channels, int& width, int& height) {
  ExrFile file(path);
  std::vector<Pixel> pixels(static_cast<std::size_t>(file.width()) * static_cast<std::size_t>(file.height()));
  file.read(channels, pixels.data(), sizeof(Pixel));
  width = file.width();
  height = file.height();
  return pixels;
}

}  // namespace

void checkImageFormat(const fs::path& path) {
  if (!isExr(path)) oiioModule(path).checkFormat(path);
}

std::string encodeImage(const fs::path& path, int width, int height, const std::vector<float>& rgb) {
  checkSize(path, width, height, rgb.size(), 3);
  if (!isExr(path)) return oiioModule(path).encodeImage(path, width, height, rgb);
  return encodeExr(path, width, height, kRgbChannels, rgb.data(), 3 * sizeof(float));
}

std::vector<float> readImage(const fs::path& path, int& width, int& height) {
  if (!isExr(path)) fail(path, "only OpenEXR images are read back (use .exr)");
  struct Rgb {
    float r, g, b;
  };
  const std::vector<Rgb> pixels = readPixels<Rgb>(path, kRgbChannels, width, height);
  std::vector<float> rgb(pixels.size() * 3);
  std::copy_n(reinterpret_cast<const float*>(pixels.data()), rgb.size(), rgb.data());
  return rgb;
}

std::string encodeHitBuffer(const fs::path& path, int width, int height, const std::vector<HitRecord>& hits) {
  if (!isExr(path)) fail(path, "hit buffers are written as OpenEXR only (use .exr)");
  checkSize(path, width, height, hits.size(), 1);
  return encodeExr(path, width, height, kHitChannels, hits.data(), sizeof(HitRecord));
}

std::vector<HitRecord> readHitBuffer(const fs::path& path, int& width, int& height) {
  return readPixels<HitRecord>(path, kHitChannels, width, height);
}

std::string encodeConeHitBuffer(const fs::path& path, int width, int height, const std::vector<ConeHitRecord>& hits) {
  if (!isExr(path)) fail(path, "cone hit buffers are written as OpenEXR only (use .exr)");
  checkSize(path, width, height, hits.size(), 1);
  return encodeExr(path, width, height, kConeHitChannels, hits.data(), sizeof(ConeHitRecord));
}

std::vector<ConeHitRecord> readConeHitBuffer(const fs::path& path, int& width, int& height) {
  return readPixels<ConeHitRecord>(path, kConeHitChannels, width, height);
}

}  // namespace passtrace
