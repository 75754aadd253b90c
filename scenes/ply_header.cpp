#include "scenes/ply_header.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene_error.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

// PLY's scalar types and their sizes in bytes, under both of the names in use.
const std::map<std::string_view, uint64_t> kTypeSizes = {
    {"char", 1},  {"uchar", 1},  {"int8", 1},    {"uint8", 1},   {"short", 2},   {"ushort", 2},
    {"int16", 2}, {"uint16", 2}, {"int", 4},     {"uint", 4},    {"int32", 4},   {"uint32", 4},
    {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};

struct Property {
  uint64_t bytes = 0;      // a scalar's size, or a list's count's size
  uint64_t itemBytes = 0;  // a list item's size; 0 for a scalar
  bool signedCount = false;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::size_t line = 0;
  uint64_t properties = 0;
  uint64_t fixedBytes = 0;  // per instance: scalars, and each list's count
  std::vector<Property> layout;
  std::vector<std::string> scalarNames;
};

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
// starting with a letter or '_': Assimp splits a line like "element 33vertex 4"
// differently from the words here and then sizes arrays from the wrong token.
bool isName(std::string_view token) {
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  return !token.empty() && letter(token[0]) && std::all_of(token.begin(), token.end(), [&](char c) {
    return letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
  });
}

std::string quoted(std::string_view token) {
  std::string out = "'";
  for (char c : token.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out + (token.size() > 40 ? "...'" : "'");
}

// A multiplication that saturates instead of wrapping (counts near 2^64).
uint64_t times(uint64_t a, uint64_t b) {
  uint64_t product = 0;
  return __builtin_mul_overflow(a, b, &product) ? UINT64_MAX : product;
}

uint64_t plus(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

// Walks a binary body instance by instance (lists make instances differ in
// size) and reports the first instance the file ends inside: Assimp would
// read past the end as zeros and fail later with a vaguer message.
void checkBinaryBody(const fs::path& file, std::ifstream& in, uint64_t start, uint64_t fileBytes, bool bigEndian,
                     const std::vector<Element>& elements) {
  uint64_t at = start;
  for (const Element& e : elements) {
    const bool hasList = std::any_of(e.layout.begin(), e.layout.end(), [](const Property& p) { return p.itemBytes > 0; });
    if (!hasList) {  // checked by the caller's size bound already
      at += e.count * e.fixedBytes;
      continue;
    }
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.layout) {
        const auto truncated = [&] {
          return SceneError(file, "binary body ends inside " + e.name + " " + std::to_string(i) + " of " +
                                      std::to_string(e.count) + " (truncated file?)");
        };
        if (p.bytes > fileBytes - std::min(at, fileBytes)) throw truncated();
        uint64_t items = 0;
        if (p.itemBytes > 0) {
          unsigned char raw[4] = {};
          in.seekg(static_cast<std::streamoff>(at));
          in.read(reinterpret_cast<char*>(raw), static_cast<std::streamsize>(p.bytes));
          for (uint64_t b = 0; b < p.bytes; ++b)
            items |= uint64_t{raw[bigEndian ? p.bytes - 1 - b : b]} << (8 * b);
          if (p.signedCount && (items >> (8 * p.bytes - 1)) != 0)
            throw SceneError(file, e.name + " " + std::to_string(i) + ": negative list length");
        }
        at = plus(at, plus(p.bytes, times(items, p.itemBytes)));
        if (at > fileBytes) throw truncated();
      }
  }
  if (at > fileBytes) throw SceneError(file, "binary body ends before its last element (truncated file?)");
}

// Walks an ASCII body line by line, one instance per line as Assimp reads it,
// and requires each line to hold exactly its instance's values: Assimp sizes
// a list from its count before reading the items, so "4000000000 1 2" would
// make it allocate 32 GB. Scalars are not parsed here; Assimp reads them.
void checkAsciiBody(const fs::path& file, std::ifstream& in, uint64_t start, std::size_t firstLine,
                    const std::vector<Element>& elements) {
  in.seekg(static_cast<std::streamoff>(start));
  std::string text;
  std::size_t number = firstLine - 1;
  for (const Element& e : elements)
    for (uint64_t i = 0; i < e.count; ++i) {
      ++number;
      const auto fail = [&](const std::string& reason) {
        throw SceneError(file, number, e.name + " " + std::to_string(i) + ": " + reason);
      };
      if (!std::getline(in, text)) fail("the file ends before this " + e.name + " (truncated file?)");
      if (!text.empty() && text.back() == '\r') text.pop_back();
      const std::vector<std::string_view> values = words(text);
      std::size_t at = 0;
      for (const Property& p : e.layout) {
        if (at >= values.size()) fail("too few values on the line");
        if (p.itemBytes == 0) {
          ++at;
          continue;
        }
        const std::string_view token = values[at++];
        uint64_t items = 0;
        const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), items);
        if (error != std::errc{} || end != token.data() + token.size())
          fail("list length " + quoted(token) + " is not a whole number");
        if (items > values.size() - at) fail("a list of " + std::to_string(items) + " values on a shorter line");
        at += static_cast<std::size_t>(items);
      }
      if (at != values.size()) fail(std::to_string(values.size()) + " values on the line, " + std::to_string(at) + " expected");
    }
}

}  // namespace

PlyHeaderSummary checkPlyHeader(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file, std::string("cannot open: ") + std::strerror(errno));
  std::string head(kMaxHeaderBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.clear();  // the read above stops at the end of a short file, setting eofbit and failbit
  in.seekg(0, std::ios::end);
  const auto fileBytes = static_cast<uint64_t>(in.tellg());

  PlyHeaderSummary summary;
  std::vector<Element> elements;
  bool haveFormat = false;
  bool bigEndian = false;
  std::size_t number = 0;
  std::size_t offset = 0;
  for (;;) {
    const std::size_t eol = head.find('\n', offset);
    if (eol == std::string::npos) {
      if (head.size() == kMaxHeaderBytes) throw SceneError(file, "PLY header longer than 1 MiB (no end_header)");
      throw SceneError(file, number + 1, "PLY header ends before end_header");
    }
    std::string_view line(head.data() + offset, eol - offset);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF headers exist
    offset = eol + 1;
    ++number;
    const auto fail = [&](const std::string& reason) { throw SceneError(file, number, reason); };
    const std::vector<std::string_view> w = words(line);
    if (number == 1) {
      if (w.size() != 1 || (w[0] != "ply" && w[0] != "PLY")) fail("not a PLY file (the first line is not 'ply')");
      continue;
    }
    // Assimp and this check could split a line with a NUL or other control
    // character differently, and then disagree about the layout.
    if (std::any_of(line.begin(), line.end(), [](char c) { return (c >= 0 && c < 0x20 && c != '\t') || c == 0x7f; }))
      fail("control character in the PLY header");
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() != 3) fail("format needs a kind and a version");
      // Which of two format lines Assimp obeys is not ours to guess.
      if (haveFormat) fail("a second format line");
      if (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")
        fail("unknown PLY format " + quoted(w[1]));
      summary.binary = w[1] != "ascii";
      bigEndian = w[1] == "binary_big_endian";
      haveFormat = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("element needs a name and a count");
      if (!isName(w[1])) fail("bad element name " + quoted(w[1]));
      Element e;
      e.name = std::string(w[1]);
      e.line = number;
      const auto [end, error] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (error != std::errc{} || end != w[2].data() + w[2].size()) fail("bad element count " + quoted(w[2]));
      elements.push_back(e);
    } else if (w[0] == "property") {
      if (elements.empty()) fail("property before any element");
      Element& e = elements.back();
      const bool list = w.size() >= 2 && w[1] == "list";
      if (list ? w.size() != 5 : w.size() != 3)
        fail(list ? "a list property needs a count type, an item type and a name" : "property needs a type and a name");
      const auto type = kTypeSizes.find(w[list ? 2 : 1]);
      if (type == kTypeSizes.end()) fail("unknown property type " + quoted(w[list ? 2 : 1]));
      if (list && kTypeSizes.find(w[3]) == kTypeSizes.end()) fail("unknown property type " + quoted(w[3]));
      if (!isName(w.back())) fail("bad property name " + quoted(w.back()));
      ++e.properties;
      e.fixedBytes += type->second;
      Property property{type->second, 0, false};
      if (list) {
        property.itemBytes = kTypeSizes.at(w[3]);
        property.signedCount = w[2] == "char" || w[2] == "short" || w[2].starts_with("int");
        if (property.bytes > 4 || w[2].starts_with("float"))
          fail("list count type " + quoted(w[2]) + " is not an integer type");
      }
      e.layout.push_back(property);
      if (!list) e.scalarNames.emplace_back(w[2]);
    } else {
      fail("unknown header keyword " + quoted(w[0]));
    }
  }
  if (!haveFormat) throw SceneError(file, number, "PLY header has no format line");

  // Each instance needs its fixed bytes (binary) or, in ASCII, a character
  // and a separator for every property.
  const uint64_t body = fileBytes - offset;
  uint64_t needed = 0;
  for (const Element& e : elements) {
    if (e.count > 0 && e.properties == 0)
      throw SceneError(file, e.line, "element '" + e.name + "' has instances but no properties");
    needed = plus(needed, times(e.count, summary.binary ? e.fixedBytes : 2 * e.properties));
    if (needed > body + 1)  // +1: the last ASCII line may lack its newline
      throw SceneError(file, e.line,
                       "element '" + e.name + "' declares " + std::to_string(e.count) + " instances, more than the " +
                           std::to_string(body) + " bytes after the header can hold");
    // A vertex without a position is no vertex (Assimp would make up zeros).
    if (e.name == "vertex")
      for (const char* axis : {"x", "y", "z"})
        if (std::find(e.scalarNames.begin(), e.scalarNames.end(), axis) == e.scalarNames.end())
          throw SceneError(file, e.line, std::string("element 'vertex' has no property ") + axis);
    if (e.name == "vertex") summary.vertices = e.count;
    if (e.name == "face" || e.name == "tristrips") summary.faces = plus(summary.faces, e.count);
  }
  in.clear();
  if (summary.binary)
    checkBinaryBody(file, in, offset, fileBytes, bigEndian, elements);
  else
    checkAsciiBody(file, in, offset, number + 1, elements);
  return summary;
}

}  // namespace passtrace
