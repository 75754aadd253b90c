#pragma once
// A PLY header, parsed and checked before any of the body is read (by
// ply_reader.h): "FILE:LINE: reason" for unknown formats and types, a second
// format line, control characters, names that are not words, malformed
// lines, a header without end_header in its first 1 MiB, a vertex element
// without x, y and z, and element counts the rest of the file is too short
// to hold (so a header claiming 2^31 vertices in a 100-byte file allocates
// nothing). The body begins right after the '\n' that ends end_header's
// line, whatever its first byte is.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace passtrace {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

// The scalar types, each under both of the names in use (char/int8, ...).
enum class PlyType : uint8_t { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::size_t plyTypeBytes(PlyType type);
bool plyTypeIsInteger(PlyType type);
const char* plyTypeName(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // a list's item type
  bool list = false;
  PlyType countType = PlyType::Uint8;  // a list's count type: an integer type
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::size_t line = 0;  // of its "element" line
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t bodyOffset = 0;  // the body's first byte in the file
  std::size_t bodyLine = 0;    // the body's first line (ASCII)
};

// `data` is the whole file. Throws SceneError.
PlyHeader parsePlyHeader(const std::filesystem::path& file, std::string_view data);

}  // namespace passtrace
