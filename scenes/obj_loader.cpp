#include "scenes/obj_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "scenes/polygon_triangulation.h"
#include "scenes/scene_error.h"
#include "scenes/scene_limits.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
// tinyobjloader stores a face's vertex count in one byte.
constexpr std::size_t kMaxFaceVertices = 255;
// tinyobjloader clamps each count of a "t" (tag) line to this.
constexpr long kMaxTagValues = 8192;

// A token fit for an error message: short and printable.
std::string quoted(std::string_view token) {
  std::string out = "'";
  for (char c : token.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return out + (token.size() > 40 ? "...'" : "'");
}

// A read-only descriptor that closes itself.
class FileDescriptor {
 public:
  // O_NONBLOCK: opening a FIFO must not wait for a writer.
  explicit FileDescriptor(const fs::path& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// Calls onLine(number, text) for every line, splitting at \n, \r\n or a lone
// \r exactly as tinyobjloader does, so both count lines alike.
template <class OnLine>
void forEachLine(const fs::path& file, OnLine&& onLine) {
  const FileDescriptor fd(file);
  if (fd.get() < 0) throw SceneError(file, std::string("cannot open: ") + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) throw SceneError(file, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw SceneError(file, "cannot open: not a regular file");
  if (static_cast<std::uintmax_t>(info.st_size) > kMaxSceneFileBytes)
    throw SceneError(file, "file too large (" + std::to_string(info.st_size) + " bytes; the limit is 2 GiB)");

  std::vector<char> chunk(std::size_t{1} << 16);
  std::string line;
  std::size_t number = 0;
  bool skipLineFeed = false;  // the last line ended in \r, which may pair with a \n
  for (;;) {
    const ssize_t n = ::read(fd.get(), chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw SceneError(file, std::string("read failed: ") + std::strerror(errno));
    if (n == 0) break;
    const char* p = chunk.data();
    const char* const end = p + n;
    while (p < end) {
      if (skipLineFeed) {
        skipLineFeed = false;
        if (*p == '\n' && ++p == end) break;
      }
      const char* eol = std::find_if(p, end, [](char c) { return c == '\n' || c == '\r'; });
      if (line.size() + static_cast<std::size_t>(eol - p) > kMaxLineBytes)
        throw SceneError(file, number + 1, "line longer than 1 MiB");
      line.append(p, eol);
      if (eol == end) break;
      skipLineFeed = *eol == '\r';
      p = eol + 1;
      onLine(++number, std::string_view(line));
      line.clear();
    }
  }
  if (!line.empty()) onLine(++number, std::string_view(line));
}

// The pre-pass. tinyobjloader reads a malformed number as 0, keeps
// out-of-range indices, skips short faces and reports no line numbers, so
// every line it would accept silently is checked here first.
class ObjChecker {
 public:
  explicit ObjChecker(const fs::path& file) : file_(file) {}

  void check(std::size_t number, std::string_view text) {
    number_ = number;
    if (text.find('\0') != std::string_view::npos) fail("NUL byte: binary data, not an OBJ file");
    tokenize(text);
    if (tokens_.empty() || tokens_[0].front() == '#') return;
    const std::string_view key = tokens_[0];
    if (key == "v") {
      numbers("vertex", 3);
      ++vertices_;
    } else if (key == "vt") {
      numbers("texture coordinate", 1);
      ++texcoords_;
    } else if (key == "vn") {
      numbers("normal", 3);
      ++normals_;
    } else if (key == "f") {
      face();
    } else if (key == "t") {
      tag();
    } else if (key == "vw") {
      skinWeights();
    }
  }

  std::size_t triangles() const { return triangles_; }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw SceneError(file_, number_, reason); }

  // Splits at spaces and tabs, the only separators tinyobjloader knows.
  void tokenize(std::string_view text) {
    tokens_.clear();
    const auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
    for (auto p = text.begin(); p != text.end();) {
      const auto begin = std::find_if_not(p, text.end(), isSpace);
      p = std::find_if(begin, text.end(), isSpace);
      if (begin != p) tokens_.emplace_back(begin, p);
    }
  }

  void numbers(const char* what, std::size_t atLeast) {
    const std::size_t count = tokens_.size() - 1;
    if (count < atLeast)
      fail(std::string(what) + " needs at least " + std::to_string(atLeast) + " numbers, got " + std::to_string(count));
    for (std::size_t i = 1; i < tokens_.size(); ++i) real(tokens_[i]);
  }

  double real(std::string_view token) {
    std::string_view digits = token;
    // from_chars rejects the leading '+' that OBJ writers may emit.
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
    double x = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
    if (error == std::errc::result_out_of_range) fail("number out of range " + quoted(token));
    if (error != std::errc{} || end != digits.data() + digits.size()) fail("bad number " + quoted(token));
    if (!std::isfinite(x)) fail("non-finite number " + quoted(token));
    if (std::fabs(x) > std::numeric_limits<float>::max()) fail("number out of range " + quoted(token));
    return x;
  }

  void face() {
    const std::size_t count = tokens_.size() - 1;
    if (count < 3) fail("face needs at least 3 vertices, got " + std::to_string(count));
    if (count > kMaxFaceVertices)
      fail("face has " + std::to_string(count) + " vertices; at most 255 are supported");
    for (std::size_t i = 1; i < tokens_.size(); ++i) corner(tokens_[i]);
    triangles_ += count - 2;
  }

  // One of v, v/vt, v//vn or v/vt/vn.
  void corner(std::string_view token) {
    std::string_view parts[3];
    std::size_t count = 0;
    for (std::string_view rest = token;;) {
      if (count == 3) fail("bad face vertex " + quoted(token));
      const std::size_t slash = rest.find('/');
      parts[count++] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    index(parts[0], vertices_, "vertex");
    if (count == 2 || (count == 3 && !parts[1].empty())) index(parts[1], texcoords_, "texture coordinate");
    if (count == 3) index(parts[2], normals_, "normal");
  }

  // OBJ indices are 1-based, negative ones count back from the latest
  // element; both must name an element defined above the face.
  void index(std::string_view token, std::size_t defined, const char* what) {
    std::string_view digits = token;
    if (digits.size() > 1 && digits[0] == '+') digits.remove_prefix(1);
    long long i = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), i);
    if (error != std::errc{} || end != digits.data() + digits.size() || digits.empty())
      fail(std::string("bad ") + what + " index " + quoted(token));
    if (i == 0) fail(std::string(what) + " index 0 (OBJ indices start at 1)");
    const long long n = static_cast<long long>(defined);
    if (i > n || i < -n)
      fail(std::string(what) + " index " + std::to_string(i) + " out of range (" + std::to_string(defined) + " defined so far)");
  }

  // tinyobjloader sizes a tag's arrays from its "ints/reals/strings" counts
  // before reading any value, so a short garbage line could claim megabytes;
  // the counts must not exceed the values present.
  void tag() {
    if (tokens_.size() < 3) return;
    long total = 0;
    std::string_view counts = tokens_[2];
    for (int part = 0; part < 3 && !counts.empty(); ++part) {
      const std::size_t slash = std::min(counts.find('/'), counts.size());
      long n = 0;
      const auto [end, error] = std::from_chars(counts.data(), counts.data() + slash, n);
      if (error != std::errc{} || end != counts.data() + slash || n < 0 || n > kMaxTagValues)
        fail("bad tag counts " + quoted(tokens_[2]));
      total += n;
      counts.remove_prefix(std::min(slash + 1, counts.size()));
    }
    if (!counts.empty()) fail("bad tag counts " + quoted(tokens_[2]));
    if (total > static_cast<long>(tokens_.size() - 3)) fail("tag declares more values than it has");
  }

  // tinyobjloader's skin-weight extension, "vw VERTEX JOINT WEIGHT ...":
  // passtrace ignores the weights, but tinyobjloader converts each joint to
  // int unchecked (undefined for 1e30), so joints must be ints.
  void skinWeights() {
    if (tokens_.size() < 2 || tokens_.size() % 2 != 0) fail("vw needs a vertex and joint/weight pairs");
    int vertex = 0;
    const std::string_view v = tokens_[1];
    const auto [end, error] = std::from_chars(v.data(), v.data() + v.size(), vertex);
    if (error != std::errc{} || end != v.data() + v.size()) fail("bad vw vertex " + quoted(v));
    for (std::size_t i = 2; i < tokens_.size(); i += 2) {
      const double joint = real(tokens_[i]);
      if (joint < 0.0 || joint > double(std::numeric_limits<int>::max())) fail("bad vw joint " + quoted(tokens_[i]));
      real(tokens_[i + 1]);
    }
  }

  const fs::path& file_;
  std::size_t number_ = 0;
  std::vector<std::string_view> tokens_;
  std::size_t vertices_ = 0;
  std::size_t texcoords_ = 0;
  std::size_t normals_ = 0;
  std::size_t triangles_ = 0;
};

// Reads the .mtl libraries an OBJ names, relative to the OBJ's directory.
// Only regular files are read (a name such as /dev/zero must not hang the
// loader); a missing library leaves its faces with the default material, as
// most viewers do.
class MtlReader final : public tinyobj::MaterialReader {
 public:
  explicit MtlReader(fs::path directory) : directory_(std::move(directory)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* ids, std::string* warning, std::string* error) override {
    const fs::path file = directory_ / name;
    std::error_code ignored;
    std::ifstream in;
    if (fs::is_regular_file(file, ignored)) in.open(file);
    if (!in.is_open()) {
      *warning += "cannot read material library " + file.string() + "\n";
      return false;
    }
    tinyobj::LoadMtl(ids, materials, &in, warning, error);
    return true;
  }

 private:
  fs::path directory_;
};

// Kd is the diffuse colour. illum 3 is the MTL model "reflection on, ray
// trace on", the only one that asks for a mirror: its Ks becomes the mirror
// reflectance. Every other model is plain diffuse. For --shading whitted:
// Ks and Ns the Phong highlight, 1 - d (dissolve) the transmission, Ni the
// index of refraction (tinyobjloader gives 1 when absent; below 1 reads as 1.5).
Material toMaterial(const tinyobj::material_t& m) {
  Material out;
  out.diffuse = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
  if (m.illum == 3) out.mirror = {m.specular[0], m.specular[1], m.specular[2]};
  out.specular = glm::max(glm::vec3(m.specular[0], m.specular[1], m.specular[2]), glm::vec3(0.0f));
  out.shininess = std::max(m.shininess, 1.0f);
  out.transmission = std::clamp(1.0f - m.dissolve, 0.0f, 1.0f);
  out.ior = m.ior >= 1.0f ? m.ior : 1.5f;
  return out;
}

}  // namespace

Scene loadObj(const fs::path& path) {
  ObjChecker checker(path);
  forEachLine(path, [&](std::size_t number, std::string_view text) { checker.check(number, text); });
  if (checker.triangles() == 0) throw SceneError(path, "no triangles");

  std::ifstream in(path);
  if (!in) throw SceneError(path, std::string("cannot open: ") + std::strerror(errno));
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> objMaterials;
  std::string warning, error;
  MtlReader mtlReader(path.parent_path());
  if (!tinyobj::LoadObj(&attrib, &shapes, &objMaterials, &warning, &error, &in, &mtlReader,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false))
    throw SceneError(path, error.empty() ? "tinyobjloader failed" : error);

  // The checker validated every index; these guards only keep a file that
  // changed between the two reads from indexing out of bounds.
  auto fetch = [&](const std::vector<tinyobj::real_t>& values, int i) {
    if (i < 0 || 3 * static_cast<std::size_t>(i) + 2 >= values.size())
      throw SceneError(path, "file changed while loading");
    return glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
  };

  bool allNormals = true;
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& corner : shape.mesh.indices) allNormals &= corner.normal_index >= 0;

  Scene scene;
  scene.name = path.stem().string();
  scene.triangles.reserve(checker.triangles());
  scene.materialIds.reserve(checker.triangles());
  if (allNormals) scene.vertexNormals.reserve(checker.triangles());
  for (const tinyobj::material_t& m : objMaterials) {
    // tinyobjloader reads a colour such as 1e39 as infinity.
    const Material material = toMaterial(m);
    const float sum = material.diffuse.r + material.diffuse.g + material.diffuse.b + material.mirror.r +
                      material.mirror.g + material.mirror.b;
    if (!std::isfinite(sum)) throw SceneError(path, "material '" + m.name + "': a colour is not a finite float");
    const float whitted = material.specular.r + material.specular.g + material.specular.b + material.shininess +
                          material.transmission + material.ior;
    if (!std::isfinite(whitted))
      throw SceneError(path, "material '" + m.name + "': Ks, Ns, d or Ni is not a finite float");
    scene.materials.push_back(material);
  }
  // Faces without a material share one default, appended after the file's.
  const auto defaultId = static_cast<uint32_t>(scene.materials.size());
  bool usesDefault = false;

  PolygonWarnings polygonWarnings;
  std::vector<glm::vec3> positions;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t first = 0;
    for (std::size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
      const std::size_t count = mesh.num_face_vertices[face];
      if (first + count > mesh.indices.size()) throw SceneError(path, "file changed while loading");
      const tinyobj::index_t* corners = &mesh.indices[first];
      const int material = mesh.material_ids[face];
      usesDefault |= material < 0;
      positions.clear();
      for (std::size_t k = 0; k < count; ++k) positions.push_back(fetch(attrib.vertices, corners[k].vertex_index));
      const PolygonTriangles polygon = triangulatePolygon(positions);
      polygonWarnings.count(polygon.shape);
      for (const auto& [a, b, c] : polygon.triangles) {
        scene.triangles.push_back(Triangle{positions[a], positions[b], positions[c]});
        if (allNormals)
          scene.vertexNormals.push_back({fetch(attrib.normals, corners[a].normal_index),
                                         fetch(attrib.normals, corners[b].normal_index),
                                         fetch(attrib.normals, corners[c].normal_index)});
        scene.materialIds.push_back(material < 0 ? defaultId : static_cast<uint32_t>(material));
      }
      first += count;
    }
  }
  if (scene.triangles.size() != checker.triangles())
    throw SceneError(path, "tinyobjloader read " + std::to_string(scene.triangles.size()) + " triangles where " +
                               std::to_string(checker.triangles()) + " were expected");
  if (usesDefault) scene.materials.push_back(Material{});
  std::cerr << polygonWarnings.text(path);
  return scene;
}

}  // namespace passtrace
