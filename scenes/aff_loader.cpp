#include "scenes/aff_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/kochanek_bartels.h"
#include "scenes/scene_error.h"
#include "scenes/scene_registry.h"
#include "scenes/tessellate.h"
#include "scenes/text_reader.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxIncludeDepth = 64;
constexpr std::size_t kMaxBlockDepth = 256;
// A file may include another many times over (instancing): these bound the
// total, so a chain of files each including the next twice cannot expand
// exponentially. BART Robots, the largest, has 835 includes and 11 MB.
constexpr std::size_t kMaxIncludes = 10000;
constexpr std::uintmax_t kMaxIncludedBytes = std::uintmax_t{1} << 30;
constexpr long long kMaxIndex = (1LL << 31) - 1;

class AffParser {
 public:
  explicit AffParser(float time) : time_(time) {
    nodes_.push_back(Node{});  // the identity root
    scene_.materials.push_back(Material{});
  }

  void parseFile(const fs::path& path) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(path, ec);
    if (ec) key = fs::absolute(path, ec);
    includeStack_.push_back(key);
    files_.push_back(path);
    const uint32_t outerFile = currentFile_;
    currentFile_ = static_cast<uint32_t>(files_.size() - 1);
    TextReader reader(path);
    parseBlock(reader, false, 0);
    currentFile_ = outerFile;
    includeStack_.pop_back();
  }

  Scene finish(const fs::path& path);

 private:
  // A transform in the tree of nested xs/x blocks; children follow parents.
  struct Node {
    int parent = -1;
    bool animated = false;
    glm::mat4 matrix{1.0f};
    std::string name;
  };

  glm::vec3 vec3(TextReader& r, const char* what) {
    const float x = r.real(what), y = r.real(what), z = r.real(what);
    return {x, y, z};
  }

  void checkRoom(TextReader& r, std::size_t more) {
    if (scene_.triangles.size() + more > kAffMaxTriangles)
      r.fail("scene exceeds " + std::to_string(kAffMaxTriangles) + " triangles");
  }

  void emit(const TriangleList& list, bool withNormals) {
    for (std::size_t i = 0; i < list.triangles.size(); ++i) {
      scene_.triangles.push_back(list.triangles[i]);
      normals_.push_back(withNormals ? list.normals[i] : std::array<glm::vec3, 3>{});
      hasNormals_.push_back(withNormals ? 1 : 0);
      triangleNode_.push_back(currentNode_);
      triangleSource_.push_back({currentFile_, commandLine_});
      scene_.materialIds.push_back(currentMaterial_);
    }
    anyNormals_ = anyNormals_ || (withNormals && !list.triangles.empty());
  }

  void parseBlock(TextReader& r, bool braced, std::size_t depth) {
    if (depth > kMaxBlockDepth) r.fail("blocks nested deeper than " + std::to_string(kMaxBlockDepth));
    const std::size_t openLine = r.lastLine();  // the '{' when braced
    while (!r.atEnd()) {
      const bool sameLine = r.nextOnSameLine();
      const std::string_view cmd = r.word("a command");
      commandLine_ = static_cast<uint32_t>(r.lastLine());
      if (cmd == "}") {
        if (braced) return;
        r.failAt(lineOfLast(r), "'}' without a matching '{'");
      } else if (cmd == "{") {
        parseBlock(r, true, depth + 1);
      } else if (cmd == "v") {
        view(r);
      } else if (cmd == "b") {
        scene_.background = vec3(r, "background colour");
      } else if (cmd == "l") {
        light(r);
      } else if (cmd == "am") {
        ambient_ = vec3(r, "ambient colour");
        haveAmbient_ = true;
      } else if (cmd == "a") {
        // BART's animation parameters: the range --frames spans by default.
        const float start = r.real("animation start time"), end = r.real("animation end time");
        r.real("animation frame count");
        if (!(start <= end)) r.failAt(r.lastLine(), "animation start time is after its end time");
        declaredRange_ = TimeRange{start, end};
      } else if (cmd == "f") {
        nffMaterial(r);
      } else if (cmd == "fm") {
        affMaterial(r);
      } else if (cmd == "c") {
        const glm::vec3 base = vec3(r, "cone base");
        const float baseRadius = r.real("cone base radius");
        const glm::vec3 apex = vec3(r, "cone apex");
        const float apexRadius = r.real("cone apex radius");
        checkRoom(r, 2 * kConeSlices);
        TriangleList list;
        tessellateCone(base, baseRadius, apex, apexRadius, list);
        emit(list, true);
      } else if (cmd == "s") {
        const glm::vec3 centre = vec3(r, "sphere centre");
        const float radius = r.real("sphere radius");
        checkRoom(r, 2 * kSphereSlices * kSphereStacks);
        TriangleList list;
        tessellateSphere(centre, radius, list);
        emit(list, true);
      } else if (cmd == "p" || cmd == "pp") {
        polygon(r, cmd == "pp");
      } else if (cmd == "m") {
        mesh(r);
      } else if (cmd == "i") {
        include(r, depth);
      } else if (cmd == "xs") {
        staticTransform(r, depth);
      } else if (cmd == "x") {
        const std::string name(r.word("transform name"));
        r.expect("{", "to open the block of 'x " + name + "'");
        Node node;
        node.parent = currentNode_;
        node.animated = true;
        node.name = name;
        withNode(std::move(node), [&] { parseBlock(r, true, depth + 1); });
      } else if (cmd == "k") {
        keyframes(r);
      } else if (TextReader::isNumber(cmd)) {
        // Stray numbers after a command's arguments on its own line are
        // ignored; one starting a line means a count was wrong.
        if (!sameLine)
          r.failAt(lineOfLast(r), "unexpected number " + TextReader::quoted(cmd) +
                                      " where a command should start (does a count above not match its data?)");
      } else {
        r.failAt(lineOfLast(r), "unknown command " + TextReader::quoted(cmd));
      }
    }
    if (braced) r.fail("unexpected end of file: the '{' of line " + std::to_string(openLine) + " is never closed");
  }

  // The line of the token consumed last.
  static std::size_t lineOfLast(const TextReader& r) { return r.lastLine(); }

  template <class Body>
  void withNode(Node node, Body&& body) {
    const int saved = currentNode_;
    nodes_.push_back(std::move(node));
    currentNode_ = static_cast<int>(nodes_.size() - 1);
    body();
    currentNode_ = saved;
  }

  void view(TextReader& r) {
    haveView_ = true;
    for (;;) {
      const std::string_view key = r.peek();
      if (key == "from") {
        r.word("from");
        scene_.camera.eye = vec3(r, "view 'from'");
      } else if (key == "at") {
        r.word("at");
        scene_.camera.lookAt = vec3(r, "view 'at'");
      } else if (key == "up") {
        r.word("up");
        scene_.camera.up = vec3(r, "view 'up'");
      } else if (key == "angle") {
        r.word("angle");
        const float angle = r.real("view angle");
        if (!(angle > 0.0f && angle < 180.0f)) r.failAt(r.lastLine(), "view angle must be in (0, 180) degrees");
        scene_.camera.fovDegrees = angle;
      } else if (key == "hither") {
        r.word("hither");
        r.real("hither distance");
      } else if (key == "resolution") {
        r.word("resolution");
        r.integer("horizontal resolution", 1 << 20);
        r.integer("vertical resolution", 1 << 20);
      } else {
        break;
      }
    }
    if (scene_.camera.eye == scene_.camera.lookAt) r.fail("view 'from' and 'at' are the same point");
  }

  void light(TextReader& r) {
    PointLight l;
    l.position = vec3(r, "light position");
    if (r.nextOnSameLine() && TextReader::isNumber(r.peek())) l.color = vec3(r, "light colour");
    lights_.push_back(l);
  }

  void nffMaterial(TextReader& r) {
    const glm::vec3 colour = vec3(r, "material colour");
    const float kd = r.real("material Kd"), ks = r.real("material Ks");
    const float shine = r.real("material shine");
    const float t = r.real("material transmittance");
    const float ior = r.real("material index of refraction");
    Material m;
    m.diffuse = kd * colour;
    if (t == 0.0f && ks >= kAffMirrorKs && shine >= kAffMirrorShine) m.mirror = glm::vec3(ks);
    setWhittedTerms(m, colour * ks, shine, t, ior);
    addMaterial(m);
  }

  void affMaterial(TextReader& r) {
    vec3(r, "material ambient colour");
    const glm::vec3 diffuse = vec3(r, "material diffuse colour");
    const glm::vec3 specular = vec3(r, "material specular colour");
    const float shine = r.real("material shine");
    const float t = r.real("material transmittance");
    const float ior = r.real("material index of refraction");
    Material m;
    m.diffuse = diffuse;
    if (t == 0.0f && shine >= kAffMirrorShine && glm::all(glm::greaterThanEqual(specular, glm::vec3(kAffMirrorKs))))
      m.mirror = specular;
    setWhittedTerms(m, specular, shine, t, ior);
    addMaterial(m);
  }

  // --shading whitted's terms: NFF's Ks colours the highlight like the
  // surface (Haines' NFF), AFF's fm gives it; T is clamped to [0, 1]; an
  // index of refraction below 1 (BART's opaque materials give 0) reads as 1.5.
  // (TextReader::real has rejected non-finite numbers.)
  static void setWhittedTerms(Material& m, glm::vec3 specular, float shine, float t, float ior) {
    m.specular = glm::max(specular, glm::vec3(0.0f));
    m.shininess = std::max(shine, 0.0f);
    m.transmission = std::clamp(t, 0.0f, 1.0f);
    m.ior = ior >= 1.0f ? ior : 1.5f;
  }

  void addMaterial(const Material& m) {
    scene_.materials.push_back(m);
    currentMaterial_ = static_cast<uint32_t>(scene_.materials.size() - 1);
  }

  void polygon(TextReader& r, bool withNormals) {
    const char* what = withNormals ? "patch vertex count" : "polygon vertex count";
    const std::size_t n = r.count(what, withNormals ? 6 : 3);
    if (n < 3) r.failAt(r.lastLine(), std::string(withNormals ? "patch" : "polygon") + " needs at least 3 vertices, got " + std::to_string(n));
    checkRoom(r, n - 2);
    std::vector<glm::vec3> vertices, normals;
    vertices.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      vertices.push_back(vec3(r, "vertex"));
      if (withNormals) normals.push_back(vec3(r, "vertex normal"));
    }
    TriangleList list;
    polygonWarnings_.count(appendPolygon(vertices, normals, list));
    emit(list, withNormals);
  }

  void mesh(TextReader& r) {
    std::vector<glm::vec3> vertices, normals;
    std::size_t texcoords = 0;
    bool haveTexcoords = false;
    for (;;) {
      const std::string_view key = r.word("'vertices', 'normals', 'texturecoords' or 'triangles' in mesh");
      if (key == "vertices") {
        const std::size_t n = r.count("vertex count", 3);
        vertices.clear();
        vertices.reserve(n);
        for (std::size_t i = 0; i < n; ++i) vertices.push_back(vec3(r, "vertex"));
      } else if (key == "normals") {
        const std::size_t n = r.count("normal count", 3);
        normals.clear();
        normals.reserve(n);
        for (std::size_t i = 0; i < n; ++i) normals.push_back(vec3(r, "normal"));
      } else if (key == "texturecoords") {
        texcoords = r.count("texture coordinate count", 2);
        haveTexcoords = true;
        if (!r.atEnd() && !TextReader::isNumber(r.peek())) r.word("texture file");  // not rendered
        for (std::size_t i = 0; i < texcoords; ++i) {
          r.real("texture coordinate");
          r.real("texture coordinate");
        }
      } else if (key == "triangles") {
        const bool withNormals = !normals.empty();
        const std::size_t perTriangle = 3 + (withNormals ? 3 : 0) + (haveTexcoords ? 3 : 0);
        const std::size_t n = r.count("triangle count", perTriangle);
        checkRoom(r, n);
        TriangleList list;
        list.triangles.reserve(n);
        if (withNormals) list.normals.reserve(n);
        for (std::size_t i = 0; i < n; ++i) {
          std::array<std::size_t, 3> v{}, nn{};
          for (auto& x : v) x = index(r, "vertex", "vertices", vertices.size());
          if (withNormals)
            for (auto& x : nn) x = index(r, "normal", "normals", normals.size());
          if (haveTexcoords)
            for (int k = 0; k < 3; ++k) index(r, "texture coordinate", "texture coordinates", texcoords);
          list.triangles.push_back({vertices[v[0]], vertices[v[1]], vertices[v[2]]});
          if (withNormals) list.normals.push_back({normals[nn[0]], normals[nn[1]], normals[nn[2]]});
        }
        emit(list, withNormals);
        return;
      } else {
        r.failAt(r.lastLine(), "expected 'vertices', 'normals', 'texturecoords' or 'triangles' in mesh, got " +
                                   TextReader::quoted(key));
      }
    }
  }

  static std::size_t index(TextReader& r, const char* what, const char* plural, std::size_t size) {
    const long long i = r.integer((std::string(what) + " index").c_str(), kMaxIndex);
    if (static_cast<std::size_t>(i) >= size)
      r.failAt(r.lastLine(), std::string(what) + " index " + std::to_string(i) + " out of range (" + std::to_string(size) +
                                 " " + (size == 1 ? what : plural) + ")");
    return static_cast<std::size_t>(i);
  }

  void include(TextReader& r, std::size_t depth) {
    r.word("include detail level");
    const std::string name(r.word("include file name"));
    const std::size_t line = r.lastLine();
    if (includeStack_.size() > kMaxIncludeDepth)
      r.failAt(line, "includes nested deeper than " + std::to_string(kMaxIncludeDepth));
    const fs::path target = r.file().parent_path() / name;
    std::error_code ec;
    if (!fs::exists(target, ec)) r.failAt(line, "included file " + TextReader::quoted(name) + " not found (" + target.string() + ")");
    if (!fs::is_regular_file(target, ec)) r.failAt(line, "included file " + TextReader::quoted(name) + " is not a regular file");
    if (++includes_ > kMaxIncludes) r.failAt(line, "more than " + std::to_string(kMaxIncludes) + " includes in all");
    includedBytes_ += fs::file_size(target, ec);
    if (includedBytes_ > kMaxIncludedBytes) r.failAt(line, "included files add up to more than 1 GiB");
    fs::path key = fs::weakly_canonical(target, ec);
    if (ec) key = fs::absolute(target, ec);
    if (std::find(includeStack_.begin(), includeStack_.end(), key) != includeStack_.end())
      r.failAt(line, "cyclic include of " + TextReader::quoted(name));
    (void)depth;
    parseFile(target);
  }

  void staticTransform(TextReader& r, std::size_t depth) {
    const glm::vec3 scale = vec3(r, "scale");
    const glm::vec3 axis = vec3(r, "rotation axis");
    const float angle = r.real("rotation angle");
    const glm::vec3 translation = vec3(r, "translation");
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translation);
    if (angle != 0.0f) {
      if (glm::length(axis) == 0.0f) r.failAt(r.lastLine(), "rotation axis is zero");
      m = glm::rotate(m, glm::radians(angle), glm::normalize(axis));
    }
    m = glm::scale(m, scale);
    r.expect("{", "to open the static transform's block");
    Node node;
    node.parent = currentNode_;
    node.matrix = m;
    withNode(std::move(node), [&] { parseBlock(r, true, depth + 1); });
  }

  void keyframes(TextReader& r) {
    const std::string name(r.word("keyframe name"));
    r.expect("{", "to open the keyframes of '" + name + "'");
    AnimatedTransform anim;
    for (;;) {
      const std::string_view key = r.word("'transl', 'rot', 'scale' or '}' in keyframes");
      std::vector<KbKey>* keys = nullptr;
      bool rotation = false;
      if (key == "}") break;
      if (key == "transl") {
        keys = &anim.translation;
      } else if (key == "rot") {
        keys = &anim.rotation;
        rotation = true;
      } else if (key == "scale") {
        keys = &anim.scale;
      } else {
        r.failAt(r.lastLine(), "expected 'transl', 'rot', 'scale' or '}' in keyframes, got " + TextReader::quoted(key));
      }
      const std::size_t n = r.count("key count", rotation ? 8 : 7);
      keys->clear();
      keys->reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        KbKey k;
        k.time = r.real("key time");
        keyRange_ = keyRange_ ? TimeRange{std::min(keyRange_->start, k.time), std::max(keyRange_->end, k.time)}
                              : TimeRange{k.time, k.time};
        const glm::vec3 value = vec3(r, "key value");  // sequenced: arguments' order is unspecified
        k.value = glm::vec4(value, rotation ? r.real("key angle") : 0.0f);
        k.tension = r.real("key tension");
        k.continuity = r.real("key continuity");
        k.bias = r.real("key bias");
        keys->push_back(k);
      }
      std::stable_sort(keys->begin(), keys->end(), [](const KbKey& a, const KbKey& b) { return a.time < b.time; });
    }
    animations_[name] = std::move(anim);
  }

  float time_;
  std::optional<TimeRange> declaredRange_, keyRange_;  // the `a` line's; the keyframes' times
  Scene scene_;
  std::vector<Node> nodes_;
  int currentNode_ = 0;
  uint32_t currentMaterial_ = 0;
  std::vector<int> triangleNode_;
  // Where each triangle's command is (an index into files_, a line), so that
  // a vertex that overflows only after the transforms can be reported there.
  std::vector<fs::path> files_;
  uint32_t currentFile_ = 0;
  uint32_t commandLine_ = 0;
  struct Source {
    uint32_t file, line;
  };
  std::vector<Source> triangleSource_;
  std::vector<std::array<glm::vec3, 3>> normals_;
  std::vector<uint8_t> hasNormals_;
  bool anyNormals_ = false;
  PolygonWarnings polygonWarnings_;  // for one warning per file, after loading
  std::map<std::string, AnimatedTransform> animations_;
  std::vector<fs::path> includeStack_;
  std::size_t includes_ = 0;
  std::uintmax_t includedBytes_ = 0;
  std::vector<PointLight> lights_;
  bool haveView_ = false;
  bool haveAmbient_ = false;
  glm::vec3 ambient_{0.0f};
};

Scene AffParser::finish(const fs::path& path) {
  // World matrices at time_ (parents precede children).
  std::vector<glm::mat4> world(nodes_.size(), glm::mat4(1.0f));
  std::vector<glm::mat3> normalMatrix(nodes_.size(), glm::mat3(1.0f));
  std::vector<uint8_t> moves(nodes_.size(), 0);  // an animated transform at or above the node
  for (std::size_t i = 1; i < nodes_.size(); ++i) {
    const Node& node = nodes_[i];
    moves[i] = node.animated || moves[static_cast<std::size_t>(node.parent)];
    glm::mat4 local = node.matrix;
    if (node.animated) {
      const auto it = animations_.find(node.name);
      local = it == animations_.end() ? glm::mat4(1.0f) : it->second.at(time_);
    }
    world[i] = world[static_cast<std::size_t>(node.parent)] * local;
    const glm::mat3 m(world[i]);
    normalMatrix[i] = glm::determinant(m) != 0.0f ? glm::transpose(glm::inverse(m)) : m;
  }
  const auto point = [](const glm::mat4& m, const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (std::size_t i = 0; i < scene_.triangles.size(); ++i) {
    const std::size_t node = static_cast<std::size_t>(triangleNode_[i]);
    Triangle& t = scene_.triangles[i];
    if (node != 0) t = {point(world[node], t.v0), point(world[node], t.v1), point(world[node], t.v2)};
    // The non-finite rule (scene.h): finite numbers can still overflow in a
    // transform (xs 1e30 ...) or a tessellation (a sphere of radius 3e38).
    if (!finite(t.v0) || !finite(t.v1) || !finite(t.v2))
      throw SceneError(files_[triangleSource_[i].file], triangleSource_[i].line,
                       std::string("non-finite vertex after ") + (node != 0 ? "the transforms" : "tessellation") +
                           " (the coordinates overflow single precision)");
  }
  if (anyNormals_) {
    scene_.vertexNormals.resize(scene_.triangles.size());
    for (std::size_t i = 0; i < scene_.triangles.size(); ++i) {
      const glm::vec3 face = faceNormal(scene_.triangles[i]);
      auto& out = scene_.vertexNormals[i];
      for (int k = 0; k < 3; ++k) {
        glm::vec3 n = face;
        if (hasNormals_[i]) {
          const glm::vec3 m = normalMatrix[static_cast<std::size_t>(triangleNode_[i])] * normals_[i][k];
          const float len = glm::length(m);
          if (len > 0.0f && std::isfinite(len)) n = m / len;
        }
        out[k] = n;
      }
    }
  }
  normals_.clear();
  scene_.animation = declaredRange_ ? declaredRange_ : keyRange_;
  if (std::any_of(triangleNode_.begin(), triangleNode_.end(), [&](int n) { return moves[static_cast<std::size_t>(n)]; }))
    for (int n : triangleNode_) scene_.moving.push_back(moves[static_cast<std::size_t>(n)]);

  const Aabb box = scene_.bounds();
  if (!haveView_) scene_.camera = framedCamera(box);
  // `k camera` places the camera at time_: BART's camera looks down -z with
  // +y up before its keyframed rotation and translation.
  if (const auto it = animations_.find("camera"); it != animations_.end()) {
    const glm::mat4 m = it->second.at(time_);
    const glm::vec3 eye(m * glm::vec4(0, 0, 0, 1));
    const glm::vec3 forward = glm::mat3(m) * glm::vec3(0, 0, -1);
    const glm::vec3 up = glm::mat3(m) * glm::vec3(0, 1, 0);
    if (glm::length(forward) > 0.0f && glm::length(up) > 0.0f && std::isfinite(eye.x + eye.y + eye.z)) {
      scene_.camera.eye = eye;
      scene_.camera.lookAt = eye + glm::normalize(forward);
      scene_.camera.up = glm::normalize(up);
    }
  }
  if (lights_.empty()) {
    scene_.light = framedLight(box);
    scene_.lightIsDefault = true;
  } else {
    scene_.light.position = lights_.front().position;
    scene_.light.color = glm::vec3(0.0f);
    for (const PointLight& l : lights_) scene_.light.color += l.color;
    if (lights_.size() > 1) scene_.lights = lights_;
  }
  // BART scenes set "am" around 1-3; a third of its mean, at most 0.4, keeps
  // shadowed streets and rooms readable without flattening the lit surfaces.
  if (haveAmbient_) scene_.ambient = std::clamp(0.3f * (ambient_.x + ambient_.y + ambient_.z) / 3.0f, 0.0f, 0.4f);
  scene_.name = path.stem().string();
  std::cerr << polygonWarnings_.text(path);
  return std::move(scene_);
}

}  // namespace

Scene loadAff(const fs::path& path, float time) {
  if (!std::isfinite(time)) throw SceneError(path, "animation time is not finite");
  AffParser parser(time);
  parser.parseFile(path);
  return parser.finish(path);
}

}  // namespace passtrace
