#include "scenes/ply_header.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "scenes/scene_error.h"
#include "scenes/text_reader.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

const std::map<std::string_view, PlyType> kTypes = {
    {"char", PlyType::Int8},       {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
    {"uint8", PlyType::Uint8},     {"short", PlyType::Int16},     {"int16", PlyType::Int16},
    {"ushort", PlyType::Uint16},   {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
    {"int32", PlyType::Int32},     {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
    {"float", PlyType::Float32},   {"float32", PlyType::Float32}, {"double", PlyType::Float64},
    {"float64", PlyType::Float64}};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t p = 0; p < line.size();) {
    const std::size_t begin = line.find_first_not_of(" \t", p);
    if (begin == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t", begin), line.size());
    out.push_back(line.substr(begin, end - begin));
    p = end;
  }
  return out;
}

// Element and property names are words of letters, digits, '_', '-' and '.'
// starting with a letter or '_'.
bool isName(std::string_view token) {
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  return !token.empty() && letter(token[0]) && std::all_of(token.begin(), token.end(), [&](char c) {
    return letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
  });
}

// A multiplication and sum that saturate instead of wrapping (counts near 2^64).
uint64_t times(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

uint64_t plus(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

// The least an instance can take: in binary its scalars and list counts; in
// ASCII a character and a separator per property.
uint64_t leastInstanceBytes(const PlyElement& e, bool binary) {
  if (!binary) return 2 * e.properties.size();
  uint64_t bytes = 0;
  for (const PlyProperty& p : e.properties) bytes += plyTypeBytes(p.list ? p.countType : p.type);
  return bytes;
}

}  // namespace

std::size_t plyTypeBytes(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::Uint8: return 1;
    case PlyType::Int16:
    case PlyType::Uint16: return 2;
    case PlyType::Int32:
    case PlyType::Uint32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool plyTypeIsInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

const char* plyTypeName(PlyType type) {
  static const char* const kNames[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
  return kNames[static_cast<std::size_t>(type)];
}

PlyHeader parsePlyHeader(const fs::path& file, std::string_view data) {
  PlyHeader header;
  bool haveFormat = false;
  std::size_t number = 0;
  std::size_t offset = 0;
  for (;;) {
    const std::size_t eol = data.find('\n', offset);
    if (eol == std::string_view::npos || eol >= kMaxHeaderBytes) {
      if (data.size() >= kMaxHeaderBytes) throw SceneError(file, "PLY header longer than 1 MiB (no end_header)");
      throw SceneError(file, number + 1, "PLY header ends before end_header");
    }
    std::string_view line = data.substr(offset, eol - offset);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF headers exist
    offset = eol + 1;
    ++number;
    const auto fail = [&](const std::string& reason) { throw SceneError(file, number, reason); };
    const std::vector<std::string_view> w = words(line);
    if (number == 1) {
      if (w.size() != 1 || (w[0] != "ply" && w[0] != "PLY")) fail("not a PLY file (the first line is not 'ply')");
      continue;
    }
    if (std::any_of(line.begin(), line.end(), [](char c) { return (c >= 0 && c < 0x20 && c != '\t') || c == 0x7f; }))
      fail("control character in the PLY header");
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() != 3) fail("format needs a kind and a version");
      // Which of two format lines the writer meant is not ours to guess.
      if (haveFormat) fail("a second format line");
      if (w[1] == "ascii")
        header.format = PlyFormat::Ascii;
      else if (w[1] == "binary_little_endian")
        header.format = PlyFormat::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian")
        header.format = PlyFormat::BinaryBigEndian;
      else
        fail("unknown PLY format " + TextReader::quoted(w[1]));
      haveFormat = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("element needs a name and a count");
      if (!isName(w[1])) fail("bad element name " + TextReader::quoted(w[1]));
      PlyElement e;
      e.name = std::string(w[1]);
      e.line = number;
      const auto [end, error] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (error != std::errc{} || end != w[2].data() + w[2].size()) fail("bad element count " + TextReader::quoted(w[2]));
      header.elements.push_back(e);
    } else if (w[0] == "property") {
      if (header.elements.empty()) fail("property before any element");
      const bool list = w.size() >= 2 && w[1] == "list";
      if (list ? w.size() != 5 : w.size() != 3)
        fail(list ? "a list property needs a count type, an item type and a name" : "property needs a type and a name");
      PlyProperty property;
      property.list = list;
      for (std::size_t k = list ? 2 : 1; k + 1 < w.size(); ++k) {
        const auto type = kTypes.find(w[k]);
        if (type == kTypes.end()) fail("unknown property type " + TextReader::quoted(w[k]));
        (list && k == 2 ? property.countType : property.type) = type->second;
      }
      if (list && !plyTypeIsInteger(property.countType))
        fail("list count type " + TextReader::quoted(w[2]) + " is not an integer type");
      if (!isName(w.back())) fail("bad property name " + TextReader::quoted(w.back()));
      property.name = std::string(w.back());
      header.elements.back().properties.push_back(property);
    } else {
      fail("unknown header keyword " + TextReader::quoted(w[0]));
    }
  }
  if (!haveFormat) throw SceneError(file, number, "PLY header has no format line");
  header.bodyOffset = offset;
  header.bodyLine = number + 1;

  const uint64_t body = data.size() - offset;
  uint64_t needed = 0;
  for (const PlyElement& e : header.elements) {
    if (e.count > 0 && e.properties.empty())
      throw SceneError(file, e.line, "element '" + e.name + "' has instances but no properties");
    needed = plus(needed, times(e.count, leastInstanceBytes(e, header.format != PlyFormat::Ascii)));
    if (needed > body + 1)  // +1: the last ASCII line may lack its newline
      throw SceneError(file, e.line,
                       "element '" + e.name + "' declares " + std::to_string(e.count) + " instances, more than the " +
                           std::to_string(body) + " bytes after the header can hold");
    // A vertex without a position is no vertex.
    if (e.name == "vertex")
      for (const char* axis : {"x", "y", "z"})
        if (std::none_of(e.properties.begin(), e.properties.end(),
                         [&](const PlyProperty& p) { return !p.list && p.name == axis; }))
          throw SceneError(file, e.line, std::string("element 'vertex' has no property ") + axis);
  }
  return header;
}

}  // namespace passtrace
