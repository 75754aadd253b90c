#include "render/exr_io.h"

#include <cstring>
#include <exception>
#include <stdexcept>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include "scenes/one_line_message.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void failExr(const fs::path& path, const std::string& reason) {
  throw std::runtime_error(path.string() + ": " + oneLineMessage(reason, "unknown OpenEXR error"));
}

// An OpenEXR output stream into a string. OutputFile seeks back to write the
// line offset table, so writes land at the current position.
class MemoryStream : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + size_t(n) > bytes_.size()) bytes_.resize(position_ + size_t(n));
    std::memcpy(bytes_.data() + position_, c, size_t(n));
    position_ += size_t(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = pos; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
  size_t position_ = 0;
};

Imf::PixelType typeOf(const ExrChannel& channel) { return channel.uint32 ? Imf::UINT : Imf::FLOAT; }

}  // namespace

std::string encodeExr(const fs::path& path, int width, int height, std::span<const ExrChannel> channels,
                      const void* pixels, std::size_t pixelBytes) {
  try {
    Imf::Header header(width, height);  // ZIP compression, no capture date: deterministic bytes
    Imf::FrameBuffer frame;
    char* base = const_cast<char*>(static_cast<const char*>(pixels));  // Slice's type; OutputFile only reads
    for (const ExrChannel& channel : channels) {
      header.channels().insert(channel.name, Imf::Channel(typeOf(channel)));
      frame.insert(channel.name, Imf::Slice(typeOf(channel), base + channel.offset, pixelBytes,
                                            pixelBytes * std::size_t(width)));
    }
    MemoryStream memory;
    {
      Imf::OutputFile file(memory, header, 1);
      file.setFrameBuffer(frame);
      file.writePixels(height);
    }  // the destructor writes the line offset table
    return memory.take();
  } catch (const std::exception& e) {
    failExr(path, e.what());
  }
}

struct ExrFile::Impl {
  explicit Impl(const fs::path& path) : file(path.c_str(), 1) {}
  Imf::InputFile file;
};

ExrFile::ExrFile(const fs::path& path) : path_(path) {
  try {
    impl_ = std::make_unique<Impl>(path);
    const Imath::Box2i window = impl_->file.header().dataWindow();
    width_ = window.max.x - window.min.x + 1;
    height_ = window.max.y - window.min.y + 1;
  } catch (const std::exception& e) {
    failExr(path, e.what());
  }
  if (width_ <= 0 || height_ <= 0) failExr(path, "not a 2D image");
}

ExrFile::~ExrFile() = default;

void ExrFile::read(std::span<const ExrChannel> channels, void* pixels, std::size_t pixelBytes) {
  const Imath::Box2i window = impl_->file.header().dataWindow();
  // Slices address pixel (x, y) of the data window, which need not start at 0.
  char* base = static_cast<char*>(pixels) -
               (std::ptrdiff_t(window.min.x) + std::ptrdiff_t(window.min.y) * width_) * std::ptrdiff_t(pixelBytes);
  Imf::FrameBuffer frame;
  for (const ExrChannel& channel : channels) {
    const Imf::Channel* stored = impl_->file.header().channels().findChannel(channel.name);
    if (!stored) failExr(path_, std::string("no channel '") + channel.name + "'");
    // A float channel may be stored as half (OpenEXR widens it); a uint32 one must be uint32.
    const bool fits = stored->type == typeOf(channel) || (!channel.uint32 && stored->type == Imf::HALF);
    if (!fits)
      failExr(path_, std::string("channel '") + channel.name + "' is " +
                      (stored->type == Imf::UINT ? "uint32" : stored->type == Imf::HALF ? "half" : "float") +
                      ", expected " + (channel.uint32 ? "uint32" : "float"));
    frame.insert(channel.name, Imf::Slice(typeOf(channel), base + channel.offset, pixelBytes,
                                          pixelBytes * std::size_t(width_)));
  }
  try {
    impl_->file.setFrameBuffer(frame);
    impl_->file.readPixels(window.min.y, window.max.y);
  } catch (const std::exception& e) {
    failExr(path_, e.what());
  }
}

}  // namespace passtrace
