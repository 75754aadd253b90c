#include "scenes/scene_export.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scenes/file_extension.h"
#include "scenes/tessellate.h"
#include "scenes/tinygltf_include.h"

namespace passtrace {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& reason) {
  throw std::runtime_error(file.string() + ": cannot export: " + reason);
}

// Shortest decimal that reads back as the same float.
std::string decimal(float v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, ec == std::errc() ? end : buf);
}

std::string triple(glm::vec3 v) { return decimal(v.x) + " " + decimal(v.y) + " " + decimal(v.z); }

// A corner in the file's units: the scene holds them times 2^scaleExponent,
// and dividing by a power of two is exact.
glm::vec3 fileUnits(const Scene& scene, glm::vec3 p) {
  return {std::ldexp(p.x, -scene.scaleExponent), std::ldexp(p.y, -scene.scaleExponent),
          std::ldexp(p.z, -scene.scaleExponent)};
}

// --- OBJ + MTL -------------------------------------------------------------------

std::string mtlText(const Scene& scene) {
  std::ostringstream out;
  out << "# passtrace export: " << scene.materials.size() << " materials, m<id> = material id\n";
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    out << "newmtl m" << i << "\nKd " << triple(m.diffuse) << "\n";
    // illum 3 ("reflection, ray traced") is what the OBJ loader reads as a mirror.
    if (m.isMirror()) out << "Ks " << triple(m.mirror) << "\nillum 3\n";
    else out << "illum 1\n";
  }
  return out.str();
}

std::string objText(const Scene& scene, const std::string& mtlName) {
  std::string out;
  out.reserve(scene.triangles.size() * 160);
  out += "# passtrace export of '" + scene.name + "': " + std::to_string(scene.triangles.size()) +
         " triangles, face k is triangle id k-1\nmtllib " + mtlName + "\n";
  for (const Triangle& t : scene.triangles)
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) out += "v " + triple(fileUnits(scene, p)) + "\n";
  const bool normals = scene.hasVertexNormals();
  if (normals)
    for (const auto& corners : scene.vertexNormals)
      for (const glm::vec3& n : corners) out += "vn " + triple(n) + "\n";
  uint32_t current = UINT32_MAX;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const uint32_t material = scene.materialIds.empty() ? 0 : scene.materialIds[i];
    if (material != current) out += "usemtl m" + std::to_string(current = material) + "\n";
    out += "f";
    for (std::size_t k = 1; k <= 3; ++k) {
      const std::string index = std::to_string(3 * i + k);
      out += " " + index + (normals ? "//" + index : "");
    }
    out += "\n";
  }
  return out;
}

std::vector<ExportedFile> exportObj(const Scene& scene, const fs::path& file) {
  fs::path mtl = file;
  mtl.replace_extension(".mtl");
  return {{mtl, mtlText(scene)}, {file, objText(scene, mtl.filename().string())}};
}

// --- glTF ------------------------------------------------------------------------

// Appends `values` to the buffer and returns an accessor over them.
int addVec3Accessor(tinygltf::Model& model, const std::vector<glm::vec3>& values, bool withBounds) {
  tinygltf::Buffer& buffer = model.buffers[0];
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = values.size() * sizeof(glm::vec3);
  view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  buffer.data.resize(buffer.data.size() + view.byteLength);
  if (!values.empty()) std::memcpy(buffer.data.data() + view.byteOffset, values.data(), view.byteLength);
  model.bufferViews.push_back(view);

  tinygltf::Accessor accessor;
  accessor.bufferView = int(model.bufferViews.size()) - 1;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = TINYGLTF_TYPE_VEC3;
  accessor.count = values.size();
  if (withBounds && !values.empty()) {  // POSITION needs min and max
    glm::vec3 lo = values[0], hi = values[0];
    for (const glm::vec3& v : values) lo = glm::min(lo, v), hi = glm::max(hi, v);
    accessor.minValues = {lo.x, lo.y, lo.z};
    accessor.maxValues = {hi.x, hi.y, hi.z};
  }
  model.accessors.push_back(accessor);
  return int(model.accessors.size()) - 1;
}

tinygltf::Model gltfModel(const Scene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "passtrace --export";
  model.buffers.resize(1);
  for (const Material& m : scene.materials) {
    tinygltf::Material out;
    const glm::vec3 color = m.isMirror() ? m.mirror : m.diffuse;
    out.pbrMetallicRoughness.baseColorFactor = {color.r, color.g, color.b, 1.0};
    // metallic 1, roughness 0: what the glTF loader reads as a mirror.
    out.pbrMetallicRoughness.metallicFactor = m.isMirror() ? 1.0 : 0.0;
    out.pbrMetallicRoughness.roughnessFactor = m.isMirror() ? 0.0 : 1.0;
    model.materials.push_back(out);
  }
  // One primitive per run of triangles with one material, in id order, so
  // that the loader, which reads primitives in order, gives the same ids.
  tinygltf::Mesh mesh;
  mesh.name = scene.name;
  const auto materialOf = [&](std::size_t i) { return scene.materialIds.empty() ? 0u : scene.materialIds[i]; };
  for (std::size_t begin = 0; begin < scene.triangles.size();) {
    std::size_t end = begin;
    while (end < scene.triangles.size() && materialOf(end) == materialOf(begin)) ++end;
    std::vector<glm::vec3> positions, normals;
    for (std::size_t i = begin; i < end; ++i) {
      const Triangle& t = scene.triangles[i];
      for (const glm::vec3& p : {t.v0, t.v1, t.v2}) positions.push_back(fileUnits(scene, p));
      if (scene.hasVertexNormals())
        for (const glm::vec3& n : scene.vertexNormals[i]) {
          // glTF's normals are unit length; the loader reads a zero one as the face's.
          const float length = glm::length(n);
          normals.push_back(length > 0.0f && std::isfinite(length) ? n / length : faceNormal(t));
        }
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = int(materialOf(begin));
    primitive.attributes["POSITION"] = addVec3Accessor(model, positions, true);
    if (!normals.empty()) primitive.attributes["NORMAL"] = addVec3Accessor(model, normals, false);
    mesh.primitives.push_back(primitive);
    begin = end;
  }
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = scene.name;
  model.nodes.push_back(node);
  tinygltf::Scene root;
  root.nodes = {0};
  model.scenes.push_back(root);
  model.defaultScene = 0;
  return model;
}

ExportedFile exportGltf(const Scene& scene, const fs::path& file, bool binary) {
  const tinygltf::Model model = gltfModel(scene);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary)) fail(file, "tinygltf could not write the model");
  return {file, out.str()};
}

}  // namespace

bool isExportFormat(const fs::path& file) {
  const std::string ext = lowerExtension(file);
  return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

std::vector<ExportedFile> exportFiles(const Scene& scene, const fs::path& file) {
  const std::string ext = lowerExtension(file);
  if (ext == ".obj") return exportObj(scene, file);
  if (ext == ".gltf") return {exportGltf(scene, file, false)};
  if (ext == ".glb") return {exportGltf(scene, file, true)};
  fail(file, "unknown format '" + ext + "' (expected .obj, .gltf or .glb)");
}

}  // namespace passtrace
