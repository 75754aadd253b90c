#pragma once
// Small PLY files written by the tests, in any of the three formats and with
// any scalar type for the positions, the list count and the indices, plus
// extra properties and elements to be skipped (the Stanford scans' layout:
// confidence and intensity on vertices, a range_grid element).

#include <bit>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace passtrace::test {

struct PlyMesh {
  std::vector<glm::vec3> vertices;
  std::vector<std::vector<int64_t>> faces;
};

struct PlyLayout {
  std::string format = "binary_little_endian";  // or "binary_big_endian", "ascii"
  std::string positionType = "float";
  std::string countType = "uchar";
  std::string indexType = "int";
  bool stanfordExtras = false;  // vertex confidence, intensity; a range_grid element before the faces
  bool extraLists = false;      // a list on every vertex and a scalar and a list on every face
  std::string indexName = "vertex_indices";
};

namespace ply_detail {

inline bool isFloat(const std::string& t) { return t == "float" || t == "float32" || t == "double" || t == "float64"; }

inline std::size_t bytesOf(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

// One value of type `type`, in the layout's format.
inline void put(std::string& out, const PlyLayout& layout, const std::string& type, double value) {
  if (layout.format == "ascii") {
    std::ostringstream s;
    s.precision(17);
    if (isFloat(type))
      s << value;
    else
      s << static_cast<int64_t>(value);
    out += (out.empty() || out.back() == '\n' ? "" : " ") + s.str();
    return;
  }
  uint64_t raw = 0;
  const std::size_t n = bytesOf(type);
  if (type == "float" || type == "float32") {
    raw = std::bit_cast<uint32_t>(static_cast<float>(value));
  } else if (n == 8 && isFloat(type)) {
    raw = std::bit_cast<uint64_t>(value);
  } else {
    raw = static_cast<uint64_t>(static_cast<int64_t>(value));
  }
  for (std::size_t b = 0; b < n; ++b) {
    const std::size_t shift = layout.format == "binary_big_endian" ? n - 1 - b : b;
    out += static_cast<char>((raw >> (8 * shift)) & 0xff);
  }
}

inline void endInstance(std::string& out, const PlyLayout& layout) {
  if (layout.format == "ascii") out += '\n';
}

}  // namespace ply_detail

inline std::string plyFile(const PlyMesh& mesh, const PlyLayout& layout) {
  using ply_detail::put;
  std::string header = "ply\nformat " + layout.format + " 1.0\ncomment passtrace test\nelement vertex " +
                       std::to_string(mesh.vertices.size()) + "\n";
  for (const char* axis : {"x", "y", "z"}) header += "property " + layout.positionType + " " + axis + "\n";
  if (layout.stanfordExtras) header += "property float confidence\nproperty float intensity\n";
  if (layout.extraLists) header += "property list ushort double ring\n";
  if (layout.stanfordExtras) header += "element range_grid 2\nproperty list uchar int vertex_indices\n";
  header += "element face " + std::to_string(mesh.faces.size()) + "\n";
  if (layout.extraLists) header += "property uchar flags\n";
  header += "property list " + layout.countType + " " + layout.indexType + " " + layout.indexName + "\n";
  if (layout.extraLists) header += "property list uint16 float32 texcoord\n";
  header += "end_header\n";

  std::string body;
  for (const glm::vec3& v : mesh.vertices) {
    for (int k = 0; k < 3; ++k) put(body, layout, layout.positionType, v[k]);
    if (layout.stanfordExtras) {
      put(body, layout, "float", 0.75);
      put(body, layout, "float", 0.5);
    }
    if (layout.extraLists) {
      put(body, layout, "ushort", 2);
      put(body, layout, "double", 1.5);
      put(body, layout, "double", -2.5);
    }
    ply_detail::endInstance(body, layout);
  }
  if (layout.stanfordExtras)
    for (int g = 0; g < 2; ++g) {  // an empty grid cell and one naming vertex 0
      put(body, layout, "uchar", g);
      if (g == 1) put(body, layout, "int", 0);
      ply_detail::endInstance(body, layout);
    }
  for (const std::vector<int64_t>& f : mesh.faces) {
    if (layout.extraLists) put(body, layout, "uchar", 7);
    put(body, layout, layout.countType, static_cast<double>(f.size()));
    for (int64_t i : f) put(body, layout, layout.indexType, static_cast<double>(i));
    if (layout.extraLists) {
      put(body, layout, "uint16", 1);
      put(body, layout, "float32", 0.25);
    }
    ply_detail::endInstance(body, layout);
  }
  return header + body;
}

}  // namespace passtrace::test
