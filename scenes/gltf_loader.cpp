#include "scenes/gltf_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scenes/gltf_animation.h"
#include "scenes/scene_error.h"
#include "scenes/scene_limits.h"
#include "scenes/scene_registry.h"
#include "scenes/tessellate.h"
#include "scenes/tinygltf_include.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// tinygltf's own file callbacks open a FIFO and wait for a writer forever,
// and size a directory by seeking to its end (a huge allocation): these read
// regular files only, the scene file and its external buffers alike.
bool isFile(const std::string& path, void*) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}
bool readRegularFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void*) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    *error += std::string("cannot open: ") + std::strerror(errno);
    return false;
  }
  struct stat info {};
  const bool regular = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  const bool small = static_cast<std::uintmax_t>(info.st_size) <= kMaxParsedFileBytes;
  if (regular && small) {
    out->resize(static_cast<std::size_t>(info.st_size));
    std::size_t filled = 0;
    for (ssize_t n = 1; filled < out->size() && n != 0;) {
      n = ::read(fd, out->data() + filled, out->size() - filled);
      if (n < 0 && errno != EINTR) break;
      if (n > 0) filled += static_cast<std::size_t>(n);
    }
    out->resize(filled);
  }
  ::close(fd);
  if (!regular) *error += "not a regular file";
  if (regular && !small) *error += "larger than 1 GiB";
  return regular && small;
}

// tinygltf converts "extras" and "extensions" into its Value type
// recursively, so JSON nested thousands of levels deep overflows the stack;
// glTF itself nests about six levels.
constexpr int kMaxJsonDepth = 256;

// The deepest nesting of [ and { outside strings.
int jsonDepth(std::string_view json) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (inString) {
      if (c == '\\') ++i;  // skips the escaped character
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// The JSON of a .gltf file, or the JSON chunk of a .glb (empty where the
// header is too broken to find it: tinygltf reports that).
std::string_view jsonOf(const std::vector<unsigned char>& bytes, bool binary) {
  const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (!binary) return all;
  uint32_t length = 0;
  if (bytes.size() < 20) return {};
  std::memcpy(&length, bytes.data() + 12, sizeof length);
  return length <= bytes.size() - 20 ? all.substr(20, length) : std::string_view{};
}

class GltfBuilder {
 public:
  GltfBuilder(const fs::path& file, const tinygltf::Model& model, float time)
      : file_(file), model_(model), time_(time) {}

  Scene build();

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw SceneError(file_, reason); }

  // The bytes of an accessor's elements: checks that they lie inside the
  // buffer view and the buffer, with the given type and component types.
  struct View {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    int componentType = 0;
  };
  View view(int accessorIndex, const std::string& where, int type, std::initializer_list<int> componentTypes) const {
    const std::string name = where + ": accessor " + std::to_string(accessorIndex);
    if (accessorIndex < 0 || static_cast<std::size_t>(accessorIndex) >= model_.accessors.size())
      fail(where + ": accessor " + std::to_string(accessorIndex) + " does not exist (" +
           std::to_string(model_.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(accessorIndex)];
    if (a.sparse.isSparse) fail(name + ": sparse accessors are not supported");
    if (a.type != type) fail(name + ": wrong element type");
    bool componentOk = false;
    for (int c : componentTypes) componentOk = componentOk || a.componentType == c;
    if (!componentOk) fail(name + ": unsupported component type " + std::to_string(a.componentType));
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
      fail(name + ": no valid buffer view (" + std::to_string(a.bufferView) + ")");
    const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model_.buffers.size())
      fail(name + ": buffer view " + std::to_string(a.bufferView) + " names no valid buffer");
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(bv.buffer)];
    const int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    if (componentSize <= 0 || components <= 0) fail(name + ": bad component type or element type");
    const std::size_t elementSize = static_cast<std::size_t>(componentSize) * static_cast<std::size_t>(components);
    const std::size_t stride = bv.byteStride == 0 ? elementSize : bv.byteStride;
    if (stride < elementSize) fail(name + ": byte stride " + std::to_string(stride) + " is smaller than an element");
    if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
      fail(name + ": buffer view " + std::to_string(a.bufferView) + " lies outside its buffer (" +
           std::to_string(buffer.data.size()) + " bytes)");
    View v;
    v.count = a.count;
    v.stride = stride;
    v.componentType = a.componentType;
    if (a.count > 0) {
      // offset + stride * (count - 1) + elementSize <= byteLength, without overflow.
      const std::size_t room = bv.byteLength;
      if (a.byteOffset > room || elementSize > room - a.byteOffset ||
          (a.count - 1) > (room - a.byteOffset - elementSize) / stride)
        fail(name + ": " + std::to_string(a.count) + " elements do not fit in buffer view " +
             std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)");
    }
    v.data = buffer.data.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  std::vector<glm::vec3> vec3s(int accessorIndex, const std::string& where) const {
    const View v = view(accessorIndex, where, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    std::vector<glm::vec3> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
      std::memcpy(&out[i], v.data + i * v.stride, sizeof(glm::vec3));
      if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z))
        fail(where + ": accessor " + std::to_string(accessorIndex) + " element " + std::to_string(i) +
             " is not finite");
    }
    return out;
  }

  // An accessor of floats, `components` (1, 3 or 4) per element: the
  // animation samplers' reader (scenes/gltf_animation.h).
  std::vector<float> floats(int accessorIndex, int components, const std::string& where) const {
    const int type = components == 1 ? TINYGLTF_TYPE_SCALAR : components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
    const View v = view(accessorIndex, where, type, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    std::vector<float> out(v.count * std::size_t(components));
    for (std::size_t i = 0; i < v.count; ++i)
      std::memcpy(&out[i * std::size_t(components)], v.data + i * v.stride, sizeof(float) * std::size_t(components));
    return out;
  }

  std::vector<uint32_t> indices(int accessorIndex, const std::string& where) const {
    const View v = view(accessorIndex, where, TINYGLTF_TYPE_SCALAR,
                        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    std::vector<uint32_t> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
      const unsigned char* p = v.data + i * v.stride;
      if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        out[i] = *p;
      } else if (v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t x;
        std::memcpy(&x, p, sizeof x);
        out[i] = x;
      } else {
        std::memcpy(&out[i], p, sizeof(uint32_t));
      }
    }
    return out;
  }

  uint32_t material(int index, const std::string& where) {
    if (index < 0) return 0;
    if (static_cast<std::size_t>(index) >= model_.materials.size())
      fail(where + ": material " + std::to_string(index) + " does not exist (" +
           std::to_string(model_.materials.size()) + " materials)");
    return static_cast<uint32_t>(index) + 1;  // 0 is Material{}
  }

  glm::mat4 localMatrix(const tinygltf::Node& node, std::size_t index) const {
    const std::string name = "node " + std::to_string(index);
    const bool animated = pose_.translation[index] || pose_.rotation[index] || pose_.scale[index];
    if (!node.matrix.empty() && animated) fail(name + ": an animated node must not have a matrix (glTF 2.0 3.7.3)");
    if (animated) return posedMatrix(node, index);
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) fail(name + ": matrix needs 16 numbers");
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<std::size_t>(i)]);
      return m;
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) fail(name + ": translation needs 3 numbers");
      m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) fail(name + ": rotation needs 4 numbers");
      const glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                        static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
      m = m * glm::mat4_cast(glm::normalize(q));
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) fail(name + ": scale needs 3 numbers");
      m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return m;
  }

  // translation * rotation * scale, each from the animation where a channel
  // targets it, else from the node.
  glm::mat4 posedMatrix(const tinygltf::Node& node, std::size_t i) const {
    glm::vec3 t(0.0f), s(1.0f);
    glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
    if (node.translation.size() == 3) t = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (node.rotation.size() == 4)
      r = glm::normalize(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
    if (node.scale.size() == 3) s = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
    if (pose_.translation[i]) t = *pose_.translation[i];
    if (pose_.rotation[i]) r = *pose_.rotation[i];
    if (pose_.scale[i]) s = *pose_.scale[i];
    return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
  }

  void visit(int index, const glm::mat4& parent, std::size_t depth, const std::string& from, bool parentMoves = false) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      fail(from + ": node " + std::to_string(index) + " does not exist (" + std::to_string(model_.nodes.size()) +
           " nodes)");
    const std::size_t i = static_cast<std::size_t>(index);
    // Nodes form strict trees (spec): a second visit is a cycle or a shared
    // child, either of which could make the walk endless or explosive.
    if (visited_[i]) fail(from + ": node " + std::to_string(index) + " has more than one parent (or a cycle)");
    visited_[i] = true;
    if (depth > kMaxNodeDepth) fail("node " + std::to_string(index) + ": nodes nested deeper than " + std::to_string(kMaxNodeDepth));
    const tinygltf::Node& node = model_.nodes[i];
    const glm::mat4 world = parent * localMatrix(node, i);
    // Moves over the animation: an animated node or one below it.
    const bool moves = parentMoves || pose_.targeted[i];
    // Every entry: finite factors can overflow in the product, and an
    // infinite off-diagonal entry turns vertices into NaN.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(world[c][r])) fail("node " + std::to_string(index) + ": transform is not finite");

    if (node.camera >= 0 && !haveCamera_) {
      if (static_cast<std::size_t>(node.camera) >= model_.cameras.size())
        fail("node " + std::to_string(index) + ": camera " + std::to_string(node.camera) + " does not exist");
      const tinygltf::Camera& camera = model_.cameras[static_cast<std::size_t>(node.camera)];
      if (camera.type == "perspective") {
        const double yfov = camera.perspective.yfov;
        if (!(yfov > 0.0 && yfov < M_PI)) fail("camera " + std::to_string(node.camera) + ": yfov must be in (0, pi)");
        const glm::vec3 eye(world * glm::vec4(0, 0, 0, 1));
        const glm::vec3 forward = glm::mat3(world) * glm::vec3(0, 0, -1);
        const glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
        if (glm::length(forward) > 0.0f && glm::length(up) > 0.0f) {
          scene_.camera = CameraSpec{eye, eye + glm::normalize(forward), glm::normalize(up),
                                     static_cast<float>(yfov * 180.0 / M_PI)};
          haveCamera_ = true;
        }
      }
    }
    if (!haveLight_) {
      const auto ext = node.extensions.find("KHR_lights_punctual");
      if (ext != node.extensions.end() && ext->second.IsObject() && ext->second.Has("light") &&
          ext->second.Get("light").IsNumber()) {
        const int li = ext->second.Get("light").GetNumberAsInt();
        if (li < 0 || static_cast<std::size_t>(li) >= model_.lights.size())
          fail("node " + std::to_string(index) + ": light " + std::to_string(li) + " does not exist (" +
               std::to_string(model_.lights.size()) + " lights)");
        const tinygltf::Light& light = model_.lights[static_cast<std::size_t>(li)];
        if (light.type == "point") {
          scene_.light.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
          scene_.light.color = glm::vec3(1.0f);
          if (light.color.size() == 3)
            scene_.light.color = glm::vec3(light.color[0], light.color[1], light.color[2]);
          // JSON numbers are doubles: 1e39 is finite there and infinite here.
          const glm::vec3& c = scene_.light.color;
          if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
            fail("node " + std::to_string(index) + ": light " + std::to_string(li) +
                 ": color is not finite in single precision");
          haveLight_ = true;
        }
      }
    }
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size())
        fail("node " + std::to_string(index) + ": mesh " + std::to_string(node.mesh) + " does not exist (" +
             std::to_string(model_.meshes.size()) + " meshes)");
      addMesh(static_cast<std::size_t>(node.mesh), world, morphWeights(node, i), moves);
    }
    for (int child : node.children) visit(child, world, depth + 1, "node " + std::to_string(index), moves);
  }

  // The node's morph-target weights: animated, else the node's, else the mesh's.
  std::vector<float> morphWeights(const tinygltf::Node& node, std::size_t i) const {
    if (pose_.weights[i]) return *pose_.weights[i];
    const std::vector<double>& w =
        !node.weights.empty() ? node.weights : model_.meshes[static_cast<std::size_t>(node.mesh)].weights;
    return std::vector<float>(w.begin(), w.end());
  }

  // Adds sum_k weight_k * target_k's `attribute` deltas to `values`.
  void morph(const tinygltf::Primitive& prim, const char* attribute, const std::vector<float>& weights,
             std::vector<glm::vec3>& values, const std::string& where) const {
    for (std::size_t k = 0; k < prim.targets.size() && k < weights.size(); ++k) {
      const auto delta = prim.targets[k].find(attribute);
      if (delta == prim.targets[k].end() || weights[k] == 0.0f) continue;
      const std::vector<glm::vec3> d = vec3s(delta->second, where + ": morph target " + std::to_string(k));
      if (d.size() != values.size())
        fail(where + ": morph target " + std::to_string(k) + " has " + std::to_string(d.size()) + " " + attribute +
             " values for " + std::to_string(values.size()) + " vertices");
      for (std::size_t j = 0; j < values.size(); ++j) values[j] += weights[k] * d[j];
    }
  }

  void addMesh(std::size_t meshIndex, const glm::mat4& world, const std::vector<float>& weights, bool moves) {
    const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
    const glm::mat3 linear(world);
    const float det = glm::determinant(linear);
    const glm::mat3 normalMatrix = det != 0.0f ? glm::transpose(glm::inverse(linear)) : linear;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
          fail(where + ": unknown mode " + std::to_string(prim.mode));
        ++skipped_;
        continue;
      }
      const auto position = prim.attributes.find("POSITION");
      if (position == prim.attributes.end()) fail(where + ": no POSITION attribute");
      std::vector<glm::vec3> positions = vec3s(position->second, where);
      std::vector<glm::vec3> normals;
      if (const auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end()) {
        normals = vec3s(n->second, where);
        if (normals.size() != positions.size())
          fail(where + ": " + std::to_string(normals.size()) + " normals for " + std::to_string(positions.size()) +
               " positions");
      }
      morph(prim, "POSITION", weights, positions, where);
      if (!normals.empty()) morph(prim, "NORMAL", weights, normals, where);

      std::vector<uint32_t> order;
      if (prim.indices >= 0) {
        order = indices(prim.indices, where);
        for (std::size_t k = 0; k < order.size(); ++k)
          if (order[k] >= positions.size())
            fail(where + ": index " + std::to_string(order[k]) + " out of range (" + std::to_string(positions.size()) +
                 " vertices)");
      } else {
        order.resize(positions.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<uint32_t>(k);
      }
      const std::size_t n = order.size();
      std::vector<std::array<uint32_t, 3>> corners;
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0)
          fail(where + ": TRIANGLES with " + std::to_string(n) + (prim.indices >= 0 ? " indices" : " vertices") +
               ", not a multiple of 3");
        for (std::size_t k = 0; k + 2 < n; k += 3) corners.push_back({order[k], order[k + 1], order[k + 2]});
      } else if (n > 0 && n < 3) {
        fail(where + ": a strip or fan needs at least 3 vertices, got " + std::to_string(n));
      } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Spec: triangle i is (i, i + 1 + i % 2, i + 2 - i % 2).
        for (std::size_t k = 0; k + 2 < n; ++k)
          corners.push_back({order[k], order[k + 1 + k % 2], order[k + 2 - k % 2]});
      } else {
        // Spec: triangle i is (i + 1, i + 2, 0).
        for (std::size_t k = 0; k + 2 < n; ++k) corners.push_back({order[k + 1], order[k + 2], order[0]});
      }
      if (scene_.triangles.size() + corners.size() > kMaxSceneTriangles)
        fail(where + ": the scene exceeds " + std::to_string(kMaxSceneTriangles) + " triangles");
      const uint32_t materialId = material(prim.material, where);
      for (auto c : corners) {
        if (det < 0.0f) std::swap(c[1], c[2]);
        Triangle t;
        t.v0 = glm::vec3(world * glm::vec4(positions[c[0]], 1.0f));
        t.v1 = glm::vec3(world * glm::vec4(positions[c[1]], 1.0f));
        t.v2 = glm::vec3(world * glm::vec4(positions[c[2]], 1.0f));
        // The non-finite rule (scene.h): a finite transform can still carry a
        // finite position past FLT_MAX.
        for (const glm::vec3& v : {t.v0, t.v1, t.v2})
          if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            fail(where + ": non-finite vertex after the node transforms (the coordinates overflow single precision)");
        scene_.triangles.push_back(t);
        scene_.materialIds.push_back(materialId);
        scene_.moving.push_back(moves ? 1 : 0);
        std::array<glm::vec3, 3> vn{};
        const glm::vec3 face = faceNormal(t);
        for (int k = 0; k < 3; ++k) {
          vn[k] = face;
          if (!normals.empty()) {
            const glm::vec3 m = normalMatrix * normals[c[static_cast<std::size_t>(k)]];
            const float len = glm::length(m);
            if (len > 0.0f && std::isfinite(len)) vn[k] = m / len;
          }
        }
        normals_.push_back(vn);
        anyNormals_ = anyNormals_ || !normals.empty();
      }
    }
  }

  fs::path file_;
  const tinygltf::Model& model_;
  Scene scene_;
  std::vector<bool> visited_;
  std::vector<std::array<glm::vec3, 3>> normals_;
  bool anyNormals_ = false;
  bool haveCamera_ = false;
  bool haveLight_ = false;
  std::size_t skipped_ = 0;
  float time_;
  GltfPose pose_;
};

// A number in material extension `ext`'s object, or `fallback` when absent.
double extensionNumber(const tinygltf::Material& material, const char* ext, const char* key, double fallback) {
  const auto found = material.extensions.find(ext);
  if (found == material.extensions.end() || !found->second.Has(key)) return fallback;
  const tinygltf::Value& v = found->second.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// --shading whitted's terms: KHR_materials_transmission's transmissionFactor
// (default 0) and KHR_materials_ior's ior (default 1.5; below 1 reads as
// 1.5); a Phong highlight from KHR_materials_specular's specularFactor times
// specularColorFactor (default none) with the exponent 2 / roughness^2 - 2
// (Blinn-Phong's match of a microfacet lobe, at least 1).
void readWhittedTerms(const tinygltf::Material& material, Material& m) {
  m.transmission = std::clamp(
      float(extensionNumber(material, "KHR_materials_transmission", "transmissionFactor", 0.0)), 0.0f, 1.0f);
  const float ior = float(extensionNumber(material, "KHR_materials_ior", "ior", 1.5));
  m.ior = ior >= 1.0f ? ior : 1.5f;
  const auto specular = material.extensions.find("KHR_materials_specular");
  if (specular != material.extensions.end()) {
    glm::vec3 colour(1.0f);
    if (specular->second.Has("specularColorFactor")) {
      const tinygltf::Value& c = specular->second.Get("specularColorFactor");
      if (c.IsArray() && c.ArrayLen() >= 3)
        for (int k = 0; k < 3; ++k) colour[k] = float(c.Get(k).GetNumberAsDouble());
    }
    m.specular = glm::max(colour, glm::vec3(0.0f)) *
                 std::max(0.0f, float(extensionNumber(material, "KHR_materials_specular", "specularFactor", 1.0)));
    const float roughness = std::clamp(float(material.pbrMetallicRoughness.roughnessFactor), 0.0f, 1.0f);
    m.shininess = std::max(1.0f, 2.0f / std::max(roughness * roughness, 1e-3f) - 2.0f);
  }
}

Scene GltfBuilder::build() {
  scene_.materials.push_back(Material{});
  for (std::size_t i = 0; i < model_.materials.size(); ++i) {
    const tinygltf::PbrMetallicRoughness& pbr = model_.materials[i].pbrMetallicRoughness;
    Material m;
    if (pbr.baseColorFactor.size() >= 3)
      m.diffuse = glm::vec3(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
    if (!std::isfinite(m.diffuse.x + m.diffuse.y + m.diffuse.z))
      fail("material " + std::to_string(i) + ": baseColorFactor is not finite");
    if (pbr.metallicFactor >= 0.9 && pbr.roughnessFactor <= 0.1) m.mirror = m.diffuse;
    readWhittedTerms(model_.materials[i], m);
    if (!std::isfinite(m.transmission + m.ior + m.shininess + m.specular.x + m.specular.y + m.specular.z))
      fail("material " + std::to_string(i) + ": a transmission, ior or specular value is not finite");
    scene_.materials.push_back(m);
  }
  visited_.assign(model_.nodes.size(), false);
  const GltfFloatReader read = [this](int accessor, int components, const std::string& where) {
    return floats(accessor, components, where);
  };
  pose_ = evaluateGltfAnimations(model_, time_, read);
  scene_.animation = pose_.range;
  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (static_cast<std::size_t>(s) >= model_.scenes.size()) fail("default scene " + std::to_string(s) + " does not exist");
    roots = model_.scenes[static_cast<std::size_t>(s)].nodes;
  } else {
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int c : node.children)
        if (c >= 0 && static_cast<std::size_t>(c) < isChild.size()) isChild[static_cast<std::size_t>(c)] = true;
    for (std::size_t i = 0; i < model_.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
  }
  for (int root : roots) visit(root, glm::mat4(1.0f), 0, "scene");
  if (anyNormals_) scene_.vertexNormals = std::move(normals_);
  if (std::none_of(scene_.moving.begin(), scene_.moving.end(), [](uint8_t m) { return m != 0; })) scene_.moving.clear();
  if (skipped_ > 0)
    std::cerr << file_.string() << ": skipped " << skipped_ << " non-triangle primitive" << (skipped_ == 1 ? "" : "s")
              << "\n";
  const Aabb box = scene_.bounds();
  if (!haveCamera_) scene_.camera = framedCamera(box);
  if (!haveLight_) scene_.light = framedLight(box), scene_.lightIsDefault = true;
  scene_.background = {0.1f, 0.12f, 0.16f};
  scene_.ambient = 0.1f;
  scene_.name = file_.stem().string();
  return std::move(scene_);
}

}  // namespace

Scene loadGltf(const fs::path& path, float time) {
  if (!std::isfinite(time)) throw SceneError(path, "animation time is not finite");
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw SceneError(path, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw SceneError(path, "cannot open: not a regular file");
  if (static_cast<std::uintmax_t>(info.st_size) > kMaxParsedFileBytes)
    throw SceneError(path, "file too large (" + std::to_string(info.st_size) + " bytes; the limit is 1 GiB)");

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skipImage, nullptr);
  tinygltf::FsCallbacks files{};
  files.FileExists = &isFile;
  files.ExpandFilePath = &tinygltf::ExpandFilePath;
  files.ReadWholeFile = &readRegularFile;
  files.WriteWholeFile = &tinygltf::WriteWholeFile;
  loader.SetFsCallbacks(files);
  tinygltf::Model model;
  std::string error, warning;
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = extension == ".glb";
  std::vector<unsigned char> bytes;
  if (!readRegularFile(&bytes, &error, path.string(), nullptr)) throw SceneError(path, error);
  if (jsonDepth(jsonOf(bytes, binary)) > kMaxJsonDepth)
    throw SceneError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  const std::string baseDir = path.parent_path().string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                              static_cast<unsigned int>(bytes.size()), baseDir)
                : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(bytes.data()),
                                             static_cast<unsigned int>(bytes.size()), baseDir);
  } catch (const std::exception& e) {
    throw SceneError(path, std::string("bad glTF: ") + e.what());
  }
  if (!ok) throw SceneError(path, error.empty() ? "tinygltf could not read the file" : error);
  return GltfBuilder(path, model, time).build();
}

}  // namespace passtrace
