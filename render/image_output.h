#pragma once
// Rendered images and hit buffers encoded in memory: each encode* returns the
// bytes of the file `path` names (the format follows its extension), for the
// run's OutputFiles (render/output_files.h) to write. OpenEXR files are
// written by the OpenEXR library (render/exr_io.h), every other format by
// OpenImageIO, loaded when first named (render/oiio_module.h); formats whose
// OpenImageIO writer cannot write to memory are refused. Every failure throws
// std::runtime_error("PATH: reason").

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace passtrace {

// Throws unless OpenImageIO can write the format the extension names to
// memory, so a tool can refuse a bad output name before it renders.
void checkImageFormat(const std::filesystem::path& path);

// rgb holds width*height*3 linear floats, row-major, row 0 the top of the
// image. The format follows the extension. Float formats (.exr, .hdr)
// get the values as they are; all others get them clamped to [0,1] and
// quantised to 8 bits with no gamma, so pixel values stay predictable.
std::string encodeImage(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb);

// Reads an OpenEXR image's R, G and B channels back as encodeImage took them.
std::vector<float> readImage(const std::filesystem::path& path, int& width, int& height);

// One pixel of a hit buffer; a miss is id 0xFFFFFFFF (kNoHit) with t = +inf.
struct HitRecord {
  float t, u, v;
  uint32_t id;
};
static_assert(sizeof(HitRecord) == 16, "HitRecord is written as OpenEXR's native pixel layout");

// OpenEXR only (anything else is refused): float32 channels "t", "u", "v" and
// a uint32 channel "id", so ids stay exact.
std::string encodeHitBuffer(const std::filesystem::path& path, int width, int height, const std::vector<HitRecord>& hits);

// Reads a hit buffer back by channel name; "id" must be stored as uint32.
std::vector<HitRecord> readHitBuffer(const std::filesystem::path& path, int& width, int& height);

// One pixel of a --cone-hits buffer: distinct triangles met (capped by
// --cone-max), the nearest one's id (kNoHit for none) and its axis distance
// (+inf for none).
struct ConeHitRecord {
  uint32_t count, id;
  float t;
};
static_assert(sizeof(ConeHitRecord) == 12, "ConeHitRecord is written as OpenEXR's native pixel layout");

// OpenEXR only: uint32 channels "count", "id" and a float32 channel "t".
std::string encodeConeHitBuffer(const std::filesystem::path& path, int width, int height,
                                const std::vector<ConeHitRecord>& hits);
std::vector<ConeHitRecord> readConeHitBuffer(const std::filesystem::path& path, int& width, int& height);

}  // namespace passtrace
