#pragma once
// glTF 2.0 animations evaluated at one time (--time): node translation,
// rotation and scale channels and morph-target weights, with the spec's
// LINEAR (rotations by shortest-path slerp), STEP and CUBICSPLINE (Hermite,
// tangents scaled by the key interval) interpolation. Before the first key a
// channel holds its first value, after the last its last. Every animation in
// the file plays at once, over the union of their key times; where two
// channels target the same node property, the later one wins.
//
// The samplers' data is read through the loader's checked accessor reader, so
// a bad accessor is the loader's one-line error.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scenes/scene.h"

namespace tinygltf {
class Model;
}

namespace passtrace {

// An accessor's floats, `components` per element; throws SceneError when the
// accessor is missing, of another type or outside its buffer.
using GltfFloatReader = std::function<std::vector<float>(int accessor, int components, const std::string& where)>;

// The animated properties of each node at one time (indexed like
// Model::nodes); unset where no channel targets the property.
struct GltfPose {
  std::vector<std::optional<glm::vec3>> translation, scale;
  std::vector<std::optional<glm::quat>> rotation;
  std::vector<std::optional<std::vector<float>>> weights;  // morph-target weights of the node's mesh
  std::vector<bool> targeted;                             // any channel targets the node
  std::optional<TimeRange> range;  // the first and last key time over every sampler; none without animations
};

GltfPose evaluateGltfAnimations(const tinygltf::Model& model, float time, const GltfFloatReader& read);

}  // namespace passtrace
