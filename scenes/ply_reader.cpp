#include "scenes/ply_reader.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/file_bytes.h"
#include "scenes/indexed_mesh.h"
#include "scenes/ply_header.h"
#include "scenes/scene_error.h"
#include "scenes/scene_limits.h"
#include "scenes/text_reader.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;


// The range of an integer type's values.
bool fits(double value, PlyType type) {
  switch (type) {
    case PlyType::Int8: return value >= INT8_MIN && value <= INT8_MAX;
    case PlyType::Uint8: return value >= 0 && value <= UINT8_MAX;
    case PlyType::Int16: return value >= INT16_MIN && value <= INT16_MAX;
    case PlyType::Uint16: return value >= 0 && value <= UINT16_MAX;
    case PlyType::Int32: return value >= INT32_MIN && value <= INT32_MAX;
    case PlyType::Uint32: return value >= 0 && value <= UINT32_MAX;
    default: return true;
  }
}

// Where the current instance is, for errors: "face 4 of 5".
struct Place {
  const PlyElement* element = nullptr;
  uint64_t index = 0;
  std::string text() const { return element->name + " " + std::to_string(index); }
};

// Binary bodies: values decoded from the bytes in the file's byte order.
class BinarySource {
 public:
  BinarySource(const fs::path& file, std::string_view data, std::size_t at, bool bigEndian)
      : file_(file), data_(data), at_(at), bigEndian_(bigEndian) {}

  void begin(const PlyElement& element, uint64_t index) { place_ = {&element, index}; }
  void end() {}

  double scalar(PlyType type) {
    const std::size_t bytes = plyTypeBytes(type);
    need(bytes);
    uint64_t raw = 0;
    for (std::size_t b = 0; b < bytes; ++b)
      raw |= uint64_t{static_cast<unsigned char>(data_[at_ + (bigEndian_ ? bytes - 1 - b : b)])} << (8 * b);
    at_ += bytes;
    switch (type) {
      case PlyType::Int8: return static_cast<int8_t>(raw);
      case PlyType::Uint8: return static_cast<uint8_t>(raw);
      case PlyType::Int16: return static_cast<int16_t>(raw);
      case PlyType::Uint16: return static_cast<uint16_t>(raw);
      case PlyType::Int32: return static_cast<int32_t>(raw);
      case PlyType::Uint32: return static_cast<uint32_t>(raw);
      case PlyType::Float32: {
        const auto bits = static_cast<uint32_t>(raw);
        float f = 0.0f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
      }
      case PlyType::Float64: {
        double d = 0.0;
        std::memcpy(&d, &raw, sizeof d);
        return d;
      }
    }
    return 0.0;
  }

  void skip(PlyType type, uint64_t items = 1) {
    const uint64_t bytes = items * plyTypeBytes(type);  // items < 2^32: no overflow
    need(bytes);
    at_ += static_cast<std::size_t>(bytes);
  }

  uint64_t listLength(PlyType countType) {
    const double n = scalar(countType);
    if (n < 0) fail("negative list length");
    need(static_cast<uint64_t>(n));  // every item takes a byte at least
    return static_cast<uint64_t>(n);
  }

  std::size_t offset() const { return at_; }

  [[noreturn]] void fail(const std::string& reason) const { throw SceneError(file_, place_.text() + ": " + reason); }
  [[noreturn]] void failPlain(const std::string& reason) const { throw SceneError(file_, reason); }

 private:
  void need(uint64_t bytes) const {
    if (bytes > data_.size() - at_)
      throw SceneError(file_, "binary body ends inside " + place_.text() + " of " + std::to_string(place_.element->count) +
                                  " (truncated file?)");
  }

  const fs::path& file_;
  std::string_view data_;
  std::size_t at_;
  bool bigEndian_;
  Place place_;
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// ASCII bodies: one instance per line, its values separated by blanks.
class AsciiSource {
 public:
  AsciiSource(const fs::path& file, std::string_view data, std::size_t at, std::size_t line)
      : file_(file), data_(data), at_(at), nextLine_(line) {}

  void begin(const PlyElement& element, uint64_t index) {
    place_ = {&element, index};
    if (!nextNonBlankLine()) fail("the file ends before this " + element.name + " (truncated file?)");
  }

  void end() {
    if (next_ != words_.size())
      fail(std::to_string(words_.size()) + " values on the line, " + std::to_string(next_) + " expected");
  }

  double scalar(PlyType type) {
    const std::string_view token = word();
    std::string_view digits = token;
    if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
    const char* first = digits.data();
    const char* last = first + digits.size();
    if (plyTypeIsInteger(type)) {
      int64_t value = 0;
      const auto [end, error] = std::from_chars(first, last, value);
      if (error != std::errc{} || end != last || digits.empty()) fail(TextReader::quoted(token) + " is not a whole number");
      if (!fits(static_cast<double>(value), type)) fail(TextReader::quoted(token) + " does not fit a " + plyTypeName(type));
      return static_cast<double>(value);
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(first, last, value);
    // Out of double's range is left to the finiteness check (as infinity).
    if ((error != std::errc{} && error != std::errc::result_out_of_range) || end != last || digits.empty())
      fail(TextReader::quoted(token) + " is not a number");
    if (error == std::errc::result_out_of_range) value = std::numeric_limits<double>::infinity();
    return value;
  }

  void skip(PlyType, uint64_t items = 1) {
    if (items > words_.size() - next_) fail("too few values on the line");
    next_ += static_cast<std::size_t>(items);
  }

  uint64_t listLength(PlyType countType) {
    const double n = scalar(countType);
    if (n < 0) fail("negative list length");
    if (n > static_cast<double>(words_.size() - next_))
      fail("a list of " + std::to_string(static_cast<uint64_t>(n)) + " values on a shorter line");
    return static_cast<uint64_t>(n);
  }

  // Whatever follows the last element must be blank.
  void finish() {
    place_ = {};
    if (nextNonBlankLine()) throw SceneError(file_, line_, "text after the last element");
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw SceneError(file_, line_, place_.text() + ": " + reason);
  }
  [[noreturn]] void failPlain(const std::string& reason) const { throw SceneError(file_, line_, reason); }

 private:
  std::string_view word() {
    if (next_ >= words_.size()) fail("too few values on the line");
    return words_[next_++];
  }

  // Splits the next line that holds a value into words_.
  bool nextNonBlankLine() {
    words_.clear();
    next_ = 0;
    while (at_ < data_.size() && words_.empty()) {
      std::size_t eol = data_.find('\n', at_);
      if (eol == std::string_view::npos) eol = data_.size();
      const std::string_view text = data_.substr(at_, eol - at_);
      at_ = eol + 1;
      line_ = nextLine_++;
      for (std::size_t p = 0; p < text.size();) {
        while (p < text.size() && isBlank(text[p])) ++p;
        const std::size_t begin = p;
        while (p < text.size() && !isBlank(text[p])) ++p;
        if (p > begin) words_.push_back(text.substr(begin, p - begin));
      }
    }
    return !words_.empty();
  }

  const fs::path& file_;
  std::string_view data_;
  std::size_t at_;
  std::size_t nextLine_;
  std::size_t line_ = 0;
  std::vector<std::string_view> words_;
  std::size_t next_ = 0;
  Place place_;
};

// What a property means to passtrace.
enum class Role { Skip, X, Y, Z, NX, NY, NZ, Corners };

std::vector<Role> vertexRoles(const PlyElement& e, bool& withNormals) {
  std::vector<Role> roles;
  int normals = 0;
  for (const PlyProperty& p : e.properties) {
    Role role = Role::Skip;
    if (!p.list) {
      const std::string_view names[] = {"x", "y", "z", "nx", "ny", "nz"};
      for (int k = 0; k < 6; ++k)
        if (p.name == names[k]) role = static_cast<Role>(k + 1);
    }
    normals += role >= Role::NX;
    roles.push_back(role);
  }
  withNormals = normals == 3;
  return roles;
}

std::vector<Role> cornerRoles(const fs::path& file, const PlyElement& e) {
  std::vector<Role> roles;
  bool found = false;
  for (const PlyProperty& p : e.properties) {
    const bool corners = !found && (p.name == "vertex_indices" || p.name == "vertex_index");
    if (corners && !p.list) throw SceneError(file, e.line, "property " + p.name + " of '" + e.name + "' is not a list");
    found |= corners;
    roles.push_back(corners ? Role::Corners : Role::Skip);
  }
  if (!found && e.count > 0)
    throw SceneError(file, e.line, "element '" + e.name + "' has no list vertex_indices (or vertex_index)");
  return roles;
}

class PlyBody {
 public:
  PlyBody(const fs::path& file, const PlyHeader& header) : file_(file), header_(header) {}

  template <class Source>
  IndexedMesh read(Source& in) {
    for (const PlyElement& e : header_.elements)
      if (e.name == "vertex") {
        if (vertices_ != nullptr) throw SceneError(file_, e.line, "a second element 'vertex'");
        vertices_ = &e;
      }
    const uint64_t vertexCount = vertices_ == nullptr ? 0 : vertices_->count;
    if (vertexCount > UINT32_MAX) throw SceneError(file_, vertices_->line, "more than 2^32 - 1 vertices");
    for (const PlyElement& e : header_.elements) {
      if (&e == vertices_)
        readVertices(in, e);
      else if (e.name == "face" || e.name == "tristrips")
        readCorners(in, e, e.name == "tristrips");
      else
        skipElement(in, e);
    }
    return std::move(mesh_);
  }

 private:
  template <class Source>
  void readVertices(Source& in, const PlyElement& e) {
    bool withNormals = false;
    const std::vector<Role> roles = vertexRoles(e, withNormals);
    mesh_.positions.resize(static_cast<std::size_t>(e.count));  // bounded by the header's size check
    if (withNormals) mesh_.normals.resize(mesh_.positions.size());
    for (uint64_t i = 0; i < e.count; ++i) {
      in.begin(e, i);
      glm::vec3& position = mesh_.positions[static_cast<std::size_t>(i)];
      for (std::size_t k = 0; k < roles.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (roles[k] == Role::Skip) {
          skipProperty(in, p);
          continue;
        }
        const auto value = static_cast<float>(in.scalar(p.type));
        const int axis = (static_cast<int>(roles[k]) - 1) % 3;
        if (roles[k] > Role::Z) {
          if (withNormals) mesh_.normals[static_cast<std::size_t>(i)][axis] = value;
          continue;
        }
        // Also a double beyond float's range.
        if (!std::isfinite(value)) in.failPlain("vertex " + std::to_string(i) + " is not finite");
        position[axis] = value;
      }
      in.end();
    }
  }

  template <class Source>
  void readCorners(Source& in, const PlyElement& e, bool strips) {
    const std::vector<Role> roles = cornerRoles(file_, e);
    const uint64_t vertexCount = vertices_ == nullptr ? 0 : vertices_->count;
    std::vector<uint32_t> strip;
    for (uint64_t i = 0; i < e.count; ++i) {
      in.begin(e, i);
      for (std::size_t k = 0; k < roles.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (roles[k] == Role::Skip) {
          skipProperty(in, p);
          continue;
        }
        const uint64_t n = in.listLength(p.countType);
        strip.clear();
        for (uint64_t c = 0; c < n; ++c) {
          const double v = in.scalar(p.type);
          if (strips && v == -1.0) {
            addStrip(strip);
            continue;
          }
          if (!(v >= 0 && v < static_cast<double>(vertexCount)) || v != std::floor(v))
            in.failPlain(e.name + " " + std::to_string(i) + " names vertex " + number(v) + " of " +
                         std::to_string(vertexCount));
          (strips ? strip : mesh_.corners).push_back(static_cast<uint32_t>(v));
        }
        if (strips)
          addStrip(strip);
        else
          mesh_.polygonEnds.push_back(mesh_.corners.size());
      }
      in.end();
    }
  }

  // A strip's triangles, (k, k+1, k+2) with every odd one flipped.
  void addStrip(std::vector<uint32_t>& strip) {
    for (std::size_t k = 0; k + 2 < strip.size(); ++k) {
      const bool odd = k % 2 == 1;
      mesh_.corners.insert(mesh_.corners.end(), {strip[k + (odd ? 1 : 0)], strip[k + (odd ? 0 : 1)], strip[k + 2]});
      mesh_.polygonEnds.push_back(mesh_.corners.size());
    }
    strip.clear();
  }

  template <class Source>
  void skipElement(Source& in, const PlyElement& e) {
    for (uint64_t i = 0; i < e.count; ++i) {
      in.begin(e, i);
      for (const PlyProperty& p : e.properties) skipProperty(in, p);
      in.end();
    }
  }

  template <class Source>
  static void skipProperty(Source& in, const PlyProperty& p) {
    if (!p.list) {
      in.skip(p.type);
      return;
    }
    in.skip(p.type, in.listLength(p.countType));
  }

  static std::string number(double v) {
    if (v == std::floor(v) && std::fabs(v) < 1e18) return std::to_string(static_cast<int64_t>(v));
    return std::to_string(v);
  }

  const fs::path& file_;
  const PlyHeader& header_;
  const PlyElement* vertices_ = nullptr;
  IndexedMesh mesh_;
};

}  // namespace

Scene loadPly(const fs::path& path) {
  const std::string data = readFileBytes(path, kMaxSceneFileBytes);
  const PlyHeader header = parsePlyHeader(path, data);
  PlyBody body(path, header);
  IndexedMesh mesh;
  if (header.format == PlyFormat::Ascii) {
    AsciiSource in(path, data, header.bodyOffset, header.bodyLine);
    mesh = body.read(in);
    in.finish();
  } else {
    BinarySource in(path, data, header.bodyOffset, header.format == PlyFormat::BinaryBigEndian);
    mesh = body.read(in);
  }
  return meshScene(path, mesh);
}

}  // namespace passtrace
