#include "scenes/assimp_loader.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <set>
#include <utility>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scenes/assimp_index_watch.h"
#include "scenes/file_extension.h"
#include "scenes/scene_error.h"
#include "scenes/scene_limits.h"
#include "scenes/scene_registry.h"
#include "scenes/tessellate.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr unsigned kMaxFaceCorners = 1024;

bool isFinite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 toGlm(const aiVector3D& v) { return {v.x, v.y, v.z}; }

// A node and its world transform, in walk order.
struct Placed {
  const aiNode* node;
  aiMatrix4x4 world;
};

class AssimpBuilder {
 public:
  AssimpBuilder(const fs::path& file, const aiScene& scene)
      : file_(file), ai_(scene), formatHasMaterials_(!kWithoutMaterials.contains(lowerExtension(file))),
        isX_(lowerExtension(file) == ".x") {}

  // Before triangulation: the walk order, each face's size, and the
  // triangle count that building would reach.
  void checkBeforeTriangulating() {
    walk();
    std::size_t triangles = 0;
    for (const Placed& p : placed_)
      for (unsigned k = 0; k < p.node->mNumMeshes; ++k) {
        const aiMesh& mesh = meshAt(p.node->mMeshes[k]);
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
          const unsigned n = mesh.mFaces[f].mNumIndices;
          if (n == 0) fail("mesh " + std::to_string(p.node->mMeshes[k]) + " face " + std::to_string(f) + " has no corners");
          // Assimp drops an X face's out-of-range indices (assimp_index_watch.h).
          if (n < 3 && isX_)
            fail("mesh " + std::to_string(p.node->mMeshes[k]) + " face " + std::to_string(f) + " has " +
                 std::to_string(n) + " corners: a face names a vertex out of range");
          if (n > kMaxFaceCorners)
            fail("mesh " + std::to_string(p.node->mMeshes[k]) + " face " + std::to_string(f) + " has " +
                 std::to_string(n) + " corners; at most " + std::to_string(kMaxFaceCorners) + " are supported");
          if (n >= 3) triangles += n - 2;
        }
        if (triangles > kMaxSceneTriangles)
          fail("the scene exceeds " + std::to_string(kMaxSceneTriangles) + " triangles");
      }
  }

  Scene build();

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw SceneError(file_, reason); }

  const aiMesh& meshAt(unsigned index) const {
    if (index >= ai_.mNumMeshes || ai_.mMeshes[index] == nullptr)
      fail("mesh " + std::to_string(index) + " does not exist (" + std::to_string(ai_.mNumMeshes) + " meshes)");
    return *ai_.mMeshes[index];
  }

  // Depth first, children in order, without recursion (a deep tree must not
  // exhaust the stack).
  void walk() {
    placed_.clear();
    if (ai_.mRootNode == nullptr) fail("no scene graph");
    std::vector<std::pair<Placed, std::size_t>> stack{{{ai_.mRootNode, ai_.mRootNode->mTransformation}, 0}};
    while (!stack.empty()) {
      const auto [p, depth] = stack.back();
      stack.pop_back();
      if (depth > kMaxNodeDepth) fail("nodes nested deeper than " + std::to_string(kMaxNodeDepth));
      placed_.push_back(p);
      for (unsigned c = p.node->mNumChildren; c-- > 0;) {
        const aiNode* child = p.node->mChildren[c];
        if (child != nullptr) stack.push_back({{child, p.world * child->mTransformation}, depth + 1});
      }
    }
  }

  void addMesh(unsigned meshIndex, const aiMatrix4x4& world);

  fs::path file_;
  const aiScene& ai_;
  // STL holds no materials: Assimp invents one, white or grey.
  static inline const std::set<std::string> kWithoutMaterials = {".stl"};
  bool formatHasMaterials_;
  bool isX_;
  std::vector<Placed> placed_;
  Scene scene_;
  std::vector<std::array<glm::vec3, 3>> normals_;
  bool anyNormals_ = false;
  std::size_t skipped_ = 0;
};

void AssimpBuilder::addMesh(unsigned meshIndex, const aiMatrix4x4& world) {
  const aiMesh& mesh = meshAt(meshIndex);
  const std::string where = "mesh " + std::to_string(meshIndex);
  if (mesh.mMaterialIndex >= ai_.mNumMaterials)
    fail(where + ": material " + std::to_string(mesh.mMaterialIndex) + " does not exist");
  for (unsigned v = 0; v < mesh.mNumVertices; ++v)
    if (!isFinite(mesh.mVertices[v])) fail(where + ": vertex " + std::to_string(v) + " is not finite");
  const aiMatrix3x3 linear(world);
  const float det = linear.Determinant();
  aiMatrix3x3 normalMatrix = linear;
  if (det != 0.0f) normalMatrix.Inverse().Transpose();
  const bool hasNormals = mesh.mNormals != nullptr;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices < 3) {
      ++skipped_;
      continue;
    }
    // aiProcess_Triangulate leaves only triangles among faces of 3 or more.
    if (face.mNumIndices != 3) fail(where + " face " + std::to_string(f) + ": not triangulated");
    std::array<unsigned, 3> c = {face.mIndices[0], face.mIndices[1], face.mIndices[2]};
    for (unsigned i : c)
      if (i >= mesh.mNumVertices)
        fail(where + " face " + std::to_string(f) + ": index " + std::to_string(i) + " out of range (" +
             std::to_string(mesh.mNumVertices) + " vertices)");
    if (det < 0.0f) std::swap(c[1], c[2]);
    Triangle t{toGlm(world * mesh.mVertices[c[0]]), toGlm(world * mesh.mVertices[c[1]]),
               toGlm(world * mesh.mVertices[c[2]])};
    for (const glm::vec3& v : {t.v0, t.v1, t.v2})
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail(where + ": non-finite vertex after the node transforms (the coordinates overflow single precision)");
    scene_.triangles.push_back(t);
    scene_.materialIds.push_back(mesh.mMaterialIndex);
    const glm::vec3 geometric = faceNormal(t);
    std::array<glm::vec3, 3> vn{geometric, geometric, geometric};
    if (hasNormals)
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 n = toGlm(normalMatrix * mesh.mNormals[c[static_cast<std::size_t>(k)]]);
        const float length = glm::length(n);
        if (length > 0.0f && std::isfinite(length)) vn[static_cast<std::size_t>(k)] = n / length;
      }
    normals_.push_back(vn);
    anyNormals_ = anyNormals_ || hasNormals;
  }
}

Scene AssimpBuilder::build() {
  for (unsigned m = 0; m < ai_.mNumMaterials; ++m) {
    const aiMaterial* material = ai_.mMaterials[m];
    Material out;
    aiString name;
    aiColor3D diffuse;
    const bool invented = !formatHasMaterials_ || material == nullptr ||
                          (material->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name == aiString(AI_DEFAULT_MATERIAL_NAME));
    if (!invented && material->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) {
      if (!std::isfinite(diffuse.r + diffuse.g + diffuse.b))
        fail("material " + std::to_string(m) + ": diffuse colour is not finite");
      out.diffuse = {diffuse.r, diffuse.g, diffuse.b};
    }
    scene_.materials.push_back(out);
  }
  if (scene_.materials.empty()) scene_.materials.push_back(Material{});
  walk();
  for (const Placed& p : placed_)
    for (unsigned k = 0; k < p.node->mNumMeshes; ++k) addMesh(p.node->mMeshes[k], p.world);
  if (scene_.triangles.empty()) fail("no triangles");
  if (anyNormals_) scene_.vertexNormals = std::move(normals_);
  if (skipped_ > 0)
    std::cerr << file_.string() << ": skipped " << skipped_ << " point and line primitive" << (skipped_ == 1 ? "" : "s")
              << "\n";
  const Aabb box = scene_.bounds();
  scene_.camera = framedCamera(box);
  scene_.light = framedLight(box);
  scene_.lightIsDefault = true;  // these formats carry no lights
  scene_.background = {0.1f, 0.12f, 0.16f};
  scene_.ambient = 0.1f;
  scene_.name = file_.stem().string();
  return std::move(scene_);
}

// Assimp's message for the last failure, or a fallback.
std::string assimpError(const Assimp::Importer& importer, const char* fallback) {
  const std::string message = importer.GetErrorString();
  return message.empty() ? fallback : message;
}

}  // namespace

const std::vector<std::string>& assimpExtensions() {
  static const std::vector<std::string> extensions = {".stl", ".fbx", ".dae", ".3ds", ".x"};
  return extensions;
}

Scene loadWithAssimp(const fs::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw SceneError(path, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw SceneError(path, "cannot open: not a regular file");
  if (static_cast<std::uintmax_t>(info.st_size) > kMaxSceneFileBytes)
    throw SceneError(path, "file too large (" + std::to_string(info.st_size) + " bytes; the limit is 2 GiB)");

  Assimp::Importer importer;
  try {
    // Read untriangulated first, so that a huge polygon is refused before
    // ear clipping spends quadratic time on it.
    const AssimpIndexWatch watch;
    const aiScene* read = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    if (!watch.finding().empty()) throw SceneError(path, watch.finding());
    if (read == nullptr) throw SceneError(path, assimpError(importer, "Assimp could not read the file"));
    AssimpBuilder(path, *read).checkBeforeTriangulating();
    // Assimp 5.2's triangulation asserts (an abort) when a mesh's primitive
    // types claim polygons that its faces lack, which its PLY reader can
    // leave behind on a malformed body: the types are recomputed from the
    // faces. The scene is the importer's until it is freed.
    for (unsigned m = 0; m < read->mNumMeshes; ++m) {
      aiMesh* mesh = const_cast<aiMesh*>(read->mMeshes[m]);
      unsigned types = 0;
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const unsigned n = mesh->mFaces[f].mNumIndices;
        if (n == 0) continue;  // refused above
        types |= n == 1 ? aiPrimitiveType_POINT : n == 2 ? aiPrimitiveType_LINE : n == 3 ? aiPrimitiveType_TRIANGLE
                                                                                         : aiPrimitiveType_POLYGON;
      }
      mesh->mPrimitiveTypes = types;
    }
    const aiScene* triangulated = importer.ApplyPostProcessing(aiProcess_Triangulate);
    if (triangulated == nullptr) throw SceneError(path, assimpError(importer, "Assimp could not triangulate"));
    return AssimpBuilder(path, *triangulated).build();
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(path, std::string("Assimp failed: ") + e.what());
  }
}

}  // namespace passtrace
