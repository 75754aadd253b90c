#include "scenes/off_reader.h"

#include <limits>
#include <string>
#include <string_view>

#include "scenes/indexed_mesh.h"
#include "scenes/text_reader.h"

namespace passtrace {
namespace {

struct Keyword {
  bool present = false;
  bool normals = false;
  bool homogeneous = false;
  bool dimension = false;
};

// [ST][C][N][4][n]OFF, or no keyword (the counts come first).
Keyword parseKeyword(std::string_view token) {
  Keyword k;
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return k;
  std::string_view prefix = token.substr(0, token.size() - 3);
  const auto take = [&](std::string_view flag) {
    if (!prefix.starts_with(flag)) return false;
    prefix.remove_prefix(flag.size());
    return true;
  };
  take("ST");
  take("C");
  k.normals = take("N");
  k.homogeneous = take("4");
  k.dimension = take("n");
  k.present = prefix.empty();
  return k;
}

void skipRestOfLine(TextReader& in) {
  while (in.nextOnSameLine()) in.word("");
}

}  // namespace

Scene loadOff(const std::filesystem::path& path) {
  TextReader in(path);
  const Keyword keyword = parseKeyword(in.peek());
  if (keyword.present) {
    in.word("OFF");
    if (keyword.homogeneous) in.fail("4OFF (homogeneous coordinates) is not supported");
    if (keyword.dimension && in.integer("dimension", 1000) != 3) in.failAt(in.lastLine(), "only 3 dimensions are supported");
  } else if (!TextReader::isNumber(in.peek())) {
    in.fail("not an OFF file (expected OFF or the vertex count, got " + TextReader::quoted(in.peek()) + ")");
  }
  IndexedMesh mesh;
  const std::size_t perVertex = keyword.normals ? 6 : 3;
  const std::size_t vertices = in.count("vertex count", perVertex);
  const std::size_t faces = in.count("face count", 1);
  skipRestOfLine(in);  // the edge count
  mesh.positions.reserve(vertices);
  if (keyword.normals) mesh.normals.reserve(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    glm::vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = in.real("vertex coordinate");
    mesh.positions.push_back(p);
    if (keyword.normals) {
      glm::vec3 n;
      for (int k = 0; k < 3; ++k) n[k] = in.real("vertex normal");
      mesh.normals.push_back(n);
    }
    skipRestOfLine(in);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    const auto corners = static_cast<std::size_t>(in.integer("face corner count", static_cast<long long>(in.remaining())));
    for (std::size_t k = 0; k < corners; ++k) {
      const long long index = in.integer("vertex index", std::numeric_limits<long long>::max());
      if (static_cast<unsigned long long>(index) >= vertices)
        in.failAt(in.lastLine(), "face " + std::to_string(f) + " names vertex " + std::to_string(index) + " of " +
                                     std::to_string(vertices));
      mesh.corners.push_back(static_cast<uint32_t>(index));
    }
    mesh.polygonEnds.push_back(mesh.corners.size());
    skipRestOfLine(in);  // a face colour
  }
  if (!in.atEnd()) in.fail("text after the last face: " + TextReader::quoted(in.peek()));
  return meshScene(path, mesh);
}

}  // namespace passtrace
