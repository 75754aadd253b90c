#pragma once
// OpenEXR files through the OpenEXR library itself: encoded in memory (for
// OutputFiles to write) and read back by channel name. render/image_output.cpp
// sends .exr here and every other format to OpenImageIO, which it loads only
// when such a file is written: OpenImageIO brings 260 shared libraries, and
// linking them was 0.5 s of CPU at every start of passtrace (73% of a
// `passtrace --version` in the dynamic loader, measured with perf), paid by
// every run that wrote no image or only EXR files.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace passtrace {

// One channel of an interleaved pixel struct: its name, whether it holds
// uint32 (else float32), and its byte offset within the pixel.
struct ExrChannel {
  const char* name;
  bool uint32;
  std::size_t offset;
};

// The bytes of an OpenEXR file (ZIP compression) of width x height pixels,
// each `pixelBytes` long, read from `pixels` per `channels`. Deterministic:
// the same pixels give the same bytes. Throws std::runtime_error("PATH: reason").
std::string encodeExr(const std::filesystem::path& path, int width, int height, std::span<const ExrChannel> channels,
                      const void* pixels, std::size_t pixelBytes);

// An OpenEXR file opened for reading. Throws std::runtime_error("PATH:
// reason") for a file OpenEXR cannot read, or that is not a 2D image.
class ExrFile {
 public:
  explicit ExrFile(const std::filesystem::path& path);
  ~ExrFile();
  int width() const { return width_; }
  int height() const { return height_; }
  // Reads the named channels into width() * height() pixels of `pixelBytes`
  // each. A channel missing, or a uint32 one stored as another type, is
  // refused (a float id would have rounded ids above 2^24).
  void read(std::span<const ExrChannel> channels, void* pixels, std::size_t pixelBytes);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path path_;
  int width_ = 0, height_ = 0;
};

}  // namespace passtrace
