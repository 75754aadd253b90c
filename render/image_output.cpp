#include "render/image_output.h"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace passtrace {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, std::string reason) {
  // OIIO's messages may end in or contain newlines; ours are one line.
  while (!reason.empty() && (reason.back() == '\n' || reason.back() == '\r')) reason.pop_back();
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  if (reason.empty()) reason = "unknown OpenImageIO error";
  throw std::runtime_error(path.string() + ": " + reason);
}

std::string lowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void checkSize(const fs::path& path, int width, int height, std::size_t values, std::size_t perPixel) {
  if (width <= 0 || height <= 0)
    fail(path, "bad image size " + std::to_string(width) + "x" + std::to_string(height));
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * perPixel;
  if (values != expected)
    fail(path, "expected " + std::to_string(expected) + " values for " + std::to_string(width) + "x" +
                   std::to_string(height) + ", got " + std::to_string(values));
}

// The writer the extension names; it must be able to write to memory.
std::unique_ptr<OIIO::ImageOutput> createWriter(const fs::path& path) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) fail(path, OIIO::geterror());
  if (!out->supports("ioproxy"))
    fail(path, std::string("OpenImageIO's ") + out->format_name() +
                   " writer cannot write to memory; use .png, .exr, .tif, .jpg or .hdr");
  return out;
}

// The file's bytes, encoded in memory so that writing them is OutputFiles'
// job, with every write checked (OpenImageIO's own file writes do not all
// report a full disk). The writer is chosen from the name.
// The same pixels give the same bytes on every run: no capture date (the
// OpenEXR writer otherwise stamps the current time into the header).
template <class WritePixels>
std::string encode(const fs::path& path, OIIO::ImageSpec spec, WritePixels&& writePixels) {
  const auto out = createWriter(path);
  spec.attribute("DateTime", "");
  OIIO::Filesystem::IOVecOutput memory;
  if (!out->set_ioproxy(&memory) || !out->open(path.string(), spec)) fail(path, out->geterror());
  if (!writePixels(*out)) {
    const std::string reason = out->geterror();
    out->close();
    fail(path, reason);
  }
  if (!out->close()) fail(path, out->geterror());
  const std::vector<unsigned char>& bytes = memory.buffer();
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace

void checkImageFormat(const fs::path& path) { createWriter(path); }

std::string encodeImage(const fs::path& path, int width, int height, const std::vector<float>& rgb) {
  checkSize(path, width, height, rgb.size(), 3);
  const std::string extension = lowerExtension(path);
  const bool floatFormat = extension == ".exr" || extension == ".hdr";
  std::vector<float> pixels = rgb;
  if (!floatFormat)  // written as [0,1] fractions of 255; NaN becomes 0
    for (float& x : pixels) x = x > 0.0f ? std::min(x, 1.0f) : 0.0f;
  const OIIO::ImageSpec spec(width, height, 3, floatFormat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  return encode(path, spec, [&](OIIO::ImageOutput& out) {
    return out.write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  });
}

std::string encodeHitBuffer(const fs::path& path, int width, int height, const std::vector<HitRecord>& hits) {
  if (lowerExtension(path) != ".exr") fail(path, "hit buffers are written as OpenEXR only (use .exr)");
  checkSize(path, width, height, hits.size(), 1);
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"t", "u", "v", "id"};
  spec.channelformats = {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT32};
  return encode(path, spec, [&](OIIO::ImageOutput& out) {
    // UNKNOWN: the data is already in the per-channel formats, which is
    // exactly HitRecord's layout.
    return out.write_image(OIIO::TypeDesc::UNKNOWN, hits.data());
  });
}

std::vector<HitRecord> readHitBuffer(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) fail(path, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) fail(path, "not a 2D image");
  struct Channel {
    const char* name;
    OIIO::TypeDesc type;
    std::size_t offset;
  };
  const Channel channels[] = {{"t", OIIO::TypeDesc::FLOAT, offsetof(HitRecord, t)},
                              {"u", OIIO::TypeDesc::FLOAT, offsetof(HitRecord, u)},
                              {"v", OIIO::TypeDesc::FLOAT, offsetof(HitRecord, v)},
                              {"id", OIIO::TypeDesc::UINT32, offsetof(HitRecord, id)}};
  std::vector<HitRecord> hits(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height));
  for (const Channel& channel : channels) {
    const int index = spec.channelindex(channel.name);
    if (index < 0) fail(path, std::string("no channel '") + channel.name + "'");
    // A float id would have rounded ids above 2^24; refuse rather than guess.
    if (channel.type == OIIO::TypeDesc::UINT32 && spec.channelformat(index) != OIIO::TypeDesc::UINT32)
      fail(path, std::string("channel '") + channel.name + "' is " + spec.channelformat(index).c_str() +
                     ", expected uint32");
    auto* first = reinterpret_cast<std::byte*>(hits.data()) + channel.offset;
    if (!in->read_image(0, 0, index, index + 1, channel.type, first, sizeof(HitRecord))) fail(path, in->geterror());
  }
  width = spec.width;
  height = spec.height;
  return hits;
}

std::string encodeConeHitBuffer(const fs::path& path, int width, int height, const std::vector<ConeHitRecord>& hits) {
  if (lowerExtension(path) != ".exr") fail(path, "cone hit buffers are written as OpenEXR only (use .exr)");
  checkSize(path, width, height, hits.size(), 1);
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"count", "id", "t"};
  spec.channelformats = {OIIO::TypeDesc::UINT32, OIIO::TypeDesc::UINT32, OIIO::TypeDesc::FLOAT};
  return encode(path, spec, [&](OIIO::ImageOutput& out) {
    return out.write_image(OIIO::TypeDesc::UNKNOWN, hits.data());  // already ConeHitRecord's per-channel layout
  });
}

std::vector<ConeHitRecord> readConeHitBuffer(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) fail(path, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1) fail(path, "not a 2D image");
  struct Channel {
    const char* name;
    OIIO::TypeDesc type;
    std::size_t offset;
  };
  const Channel channels[] = {{"count", OIIO::TypeDesc::UINT32, offsetof(ConeHitRecord, count)},
                              {"id", OIIO::TypeDesc::UINT32, offsetof(ConeHitRecord, id)},
                              {"t", OIIO::TypeDesc::FLOAT, offsetof(ConeHitRecord, t)}};
  std::vector<ConeHitRecord> hits(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height));
  for (const Channel& channel : channels) {
    const int index = spec.channelindex(channel.name);
    if (index < 0) fail(path, std::string("no channel '") + channel.name + "'");
    if (spec.channelformat(index) != channel.type)
      fail(path, std::string("channel '") + channel.name + "' is " + spec.channelformat(index).c_str() + ", expected " +
                     channel.type.c_str());
    auto* first = reinterpret_cast<std::byte*>(hits.data()) + channel.offset;
    if (!in->read_image(0, 0, index, index + 1, channel.type, first, sizeof(ConeHitRecord))) fail(path, in->geterror());
  }
  width = spec.width;
  height = spec.height;
  return hits;
}

}  // namespace passtrace
