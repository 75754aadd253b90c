#include "scenes/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "scenes/scene_error.h"
#include "scenes/tinygltf_include.h"

namespace passtrace {
namespace {

enum class Interpolation { Linear, Step, CubicSpline };

// One sampler's keys: `width` floats per value (3, 4, or the number of morph
// targets); a cubic spline stores in-tangent, value, out-tangent per key.
struct Sampler {
  std::vector<float> times;
  std::vector<float> values;
  std::size_t width = 0;
  Interpolation interpolation = Interpolation::Linear;

  const float* at(std::size_t key, int part) const {  // part: 0 in-tangent, 1 value, 2 out-tangent
    return interpolation == Interpolation::CubicSpline ? &values[(3 * key + std::size_t(part)) * width]
                                                       : &values[key * width];
  }
};

std::string where(std::size_t animation, std::size_t index, const char* what) {
  return "animation " + std::to_string(animation) + " " + what + " " + std::to_string(index);
}

Sampler readSampler(const tinygltf::Model& model, std::size_t a, std::size_t s, std::size_t width,
                    const GltfFloatReader& read, const std::string& channel) {
  const tinygltf::AnimationSampler& in = model.animations[a].samplers[s];
  const std::string name = where(a, s, "sampler");
  Sampler out;
  out.width = width;
  if (in.interpolation == "STEP") out.interpolation = Interpolation::Step;
  else if (in.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
  else if (in.interpolation.empty() || in.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
  else throw SceneError(name + ": unknown interpolation '" + in.interpolation + "'");
  out.times = read(in.input, 1, name + " input");
  if (out.times.empty()) throw SceneError(name + ": no keys");
  for (std::size_t k = 0; k < out.times.size(); ++k)
    if (!std::isfinite(out.times[k]) || (k > 0 && out.times[k] < out.times[k - 1]))
      throw SceneError(name + ": key times must be finite and increasing");
  // Weights are scalars, `width` of them per key; the rest are vec3/vec4.
  const int components = channel == "weights" ? 1 : int(width);
  out.values = read(in.output, components, name + " output");
  const std::size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3 : 1) * width;
  if (out.values.size() != out.times.size() * perKey)
    throw SceneError(name + ": " + std::to_string(out.values.size()) + " output values for " +
                     std::to_string(out.times.size()) + " keys of " + std::to_string(perKey));
  for (float v : out.values)
    if (!std::isfinite(v)) throw SceneError(name + ": output is not finite");
  return out;
}

// The sampler's value at `time`, `width` floats; rotations are normalized by
// the caller.
std::vector<float> sample(const Sampler& s, float time, bool rotation) {
  const std::size_t n = s.times.size(), w = s.width;
  std::vector<float> out(w);
  const auto copy = [&](std::size_t key) { std::copy_n(s.at(key, 1), w, out.begin()); };
  if (n == 1 || time <= s.times.front()) {
    copy(0);
    return out;
  }
  if (time >= s.times.back()) {
    copy(n - 1);
    return out;
  }
  const std::size_t k = std::size_t(std::upper_bound(s.times.begin(), s.times.end(), time) - s.times.begin()) - 1;
  const float t0 = s.times[k], t1 = s.times[k + 1], d = t1 - t0;
  const float u = d > 0.0f ? (time - t0) / d : 0.0f;
  switch (s.interpolation) {
    case Interpolation::Step:
      copy(k);
      break;
    case Interpolation::Linear:
      if (rotation) {
        const float* a = s.at(k, 1);
        const float* b = s.at(k + 1, 1);
        const glm::quat q = glm::slerp(glm::quat(a[3], a[0], a[1], a[2]), glm::quat(b[3], b[0], b[1], b[2]), u);
        out = {q.x, q.y, q.z, q.w};
      } else {
        for (std::size_t i = 0; i < w; ++i) out[i] = (1.0f - u) * s.at(k, 1)[i] + u * s.at(k + 1, 1)[i];
      }
      break;
    case Interpolation::CubicSpline: {
      // Hermite basis; the stored tangents are per unit time, so scaled by d.
      const float u2 = u * u, u3 = u2 * u;
      const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (std::size_t i = 0; i < w; ++i)
        out[i] = h00 * s.at(k, 1)[i] + h10 * d * s.at(k, 2)[i] + h01 * s.at(k + 1, 1)[i] + h11 * d * s.at(k + 1, 0)[i];
      break;
    }
  }
  return out;
}

// Floats per value of a channel's path; 0 for an unknown path.
std::size_t widthOf(const tinygltf::Model& model, const tinygltf::AnimationChannel& c) {
  if (c.target_path == "translation" || c.target_path == "scale") return 3;
  if (c.target_path == "rotation") return 4;
  if (c.target_path == "weights") {
    const tinygltf::Node& node = model.nodes[std::size_t(c.target_node)];
    if (node.mesh < 0 || std::size_t(node.mesh) >= model.meshes.size() || model.meshes[std::size_t(node.mesh)].primitives.empty())
      return 0;
    return model.meshes[std::size_t(node.mesh)].primitives[0].targets.size();
  }
  return 0;
}

// Calls f(animation, channel, sampler) for every channel that targets a node
// property passtrace animates; checks the indices on the way.
template <typename F>
void forEachChannel(const tinygltf::Model& model, const GltfFloatReader& read, F&& f) {
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& animation = model.animations[a];
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      const std::string name = where(a, c, "channel");
      if (channel.target_node < 0) continue;  // the spec allows channels for extensions
      if (std::size_t(channel.target_node) >= model.nodes.size())
        throw SceneError(name + ": node " + std::to_string(channel.target_node) + " does not exist");
      if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size())
        throw SceneError(name + ": sampler " + std::to_string(channel.sampler) + " does not exist");
      const std::size_t width = widthOf(model, channel);
      if (width == 0) continue;  // a path we do not animate, or weights of a mesh without targets
      f(channel, readSampler(model, a, std::size_t(channel.sampler), width, read, channel.target_path));
    }
  }
}

}  // namespace

GltfPose evaluateGltfAnimations(const tinygltf::Model& model, float time, const GltfFloatReader& read) {
  const std::size_t n = model.nodes.size();
  GltfPose pose;
  pose.translation.resize(n), pose.scale.resize(n), pose.rotation.resize(n), pose.weights.resize(n);
  pose.targeted.assign(n, false);
  forEachChannel(model, read, [&](const tinygltf::AnimationChannel& c, const Sampler& s) {
    const std::size_t node = std::size_t(c.target_node);
    const TimeRange keys{s.times.front(), s.times.back()};
    pose.range = pose.range ? TimeRange{std::min(pose.range->start, keys.start), std::max(pose.range->end, keys.end)} : keys;
    const std::vector<float> v = sample(s, time, c.target_path == "rotation");
    pose.targeted[node] = true;
    if (c.target_path == "translation") pose.translation[node] = glm::vec3(v[0], v[1], v[2]);
    else if (c.target_path == "scale") pose.scale[node] = glm::vec3(v[0], v[1], v[2]);
    else if (c.target_path == "rotation") {
      const glm::quat q(v[3], v[0], v[1], v[2]);
      pose.rotation[node] = glm::length(q) > 0.0f ? glm::normalize(q) : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    }
    else pose.weights[node] = v;
  });
  return pose;
}

}  // namespace passtrace
