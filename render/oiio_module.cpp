// libpasstrace_oiio.so: images in every format but OpenEXR, encoded in memory
// by OpenImageIO (render/oiio_module.h). Formats whose OpenImageIO writer
// cannot write to memory are refused.
#include "render/oiio_module.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "scenes/file_extension.h"
#include "scenes/one_line_message.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& reason) {
  throw std::runtime_error(path.string() + ": " + oneLineMessage(reason, "unknown OpenImageIO error"));
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

void checkFormat(const fs::path& path) { createWriter(path); }

// Float formats (.hdr) get the values as they are; all others get them
// clamped to [0,1] and quantised to 8 bits with no gamma. No capture date, so
// the same pixels give the same bytes.
std::string encodeImage(const fs::path& path, int width, int height, const std::vector<float>& rgb) {
  const auto out = createWriter(path);
  const bool floatFormat = lowerExtension(path) == ".hdr";
  std::vector<float> pixels = rgb;
  if (!floatFormat)  // written as [0,1] fractions of 255; NaN becomes 0
    for (float& x : pixels) x = x > 0.0f ? std::min(x, 1.0f) : 0.0f;
  OIIO::ImageSpec spec(width, height, 3, floatFormat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.attribute("DateTime", "");
  OIIO::Filesystem::IOVecOutput memory;
  if (!out->set_ioproxy(&memory) || !out->open(path.string(), spec)) fail(path, out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) {
    const std::string reason = out->geterror();
    out->close();
    fail(path, reason);
  }
  if (!out->close()) fail(path, out->geterror());
  const std::vector<unsigned char>& bytes = memory.buffer();
  return std::string(bytes.begin(), bytes.end());
}

const OiioModule kModule{checkFormat, encodeImage};

}  // namespace
}  // namespace passtrace

extern "C" const passtrace::OiioModule* passtrace_oiio_module() { return &passtrace::kModule; }
