#include "accel/kd/kd_texels.h"

#include <span>
#include <stdexcept>

#include "accel/kd/kd_compact_node.h"
#include "accel/reference_lists.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

float packedParent(const KdNode& node) { return node.parent == kNoHit ? -1.0f : packIndex(node.parent); }

KdTexels flatten(const KdTree& tree, size_t triangleCount, uint32_t stride) {
  KdTexels out;
  out.nodeStride = stride;
  out.nodes.reserve(tree.nodes.size() * stride);
  ReferenceLists lists;
  for (const KdNode& node : tree.nodes) {
    if (node.isLeaf()) {
      float list = -1.0f;
      if (node.refCount > 0) {
        const std::span<const uint32_t> refs(tree.references.data() + node.firstRef, node.refCount);
        list = packIndex(lists.append(refs));
      }
      out.nodes.emplace_back(0.0f, 0.0f, packedParent(node), list);
    } else {
      out.nodes.emplace_back(packIndex(node.rightChild), node.split, packedParent(node),
                             -(static_cast<float>(node.axis) + 2.0f));
    }
    if (stride == kKdBacktrackStride) {
      out.nodes.emplace_back(node.box.min, 0.0f);
      out.nodes.emplace_back(node.box.max, 0.0f);
    }
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  out.floatsPerTriangle =
      triangleCount == 0 ? 0.0
                         : (4.0 * stride * static_cast<double>(tree.nodes.size()) + static_cast<double>(out.listEntries)) /
                               static_cast<double>(triangleCount);
  return out;
}

}  // namespace

KdTexels flattenKdRestart(const KdTree& tree, size_t triangleCount) {
  return flatten(tree, triangleCount, kKdRestartStride);
}

KdTexels flattenKdBacktrack(const KdTree& tree, size_t triangleCount) {
  return flatten(tree, triangleCount, kKdBacktrackStride);
}

KdTexels flattenKdCompact(const KdTree& tree, size_t triangleCount) {
  KdTexels out;
  out.nodeStride = 0;
  out.nodes.assign((tree.nodes.size() + 1) / 2, glm::vec4(0.0f));
  ReferenceLists lists;
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode& node = tree.nodes[i];
    glm::vec2 packed;
    if (node.isLeaf()) {
      uint32_t payload = 0;
      if (node.refCount > 0)
        payload = lists.append(std::span<const uint32_t>(tree.references.data() + node.firstRef, node.refCount)) + 1;
      if (payload > kKdCompactMaxPayload) throw std::length_error("kd-compact: too many triangle references");
      packed = encodeKdCompactNode(0.0f, kKdCompactLeafCode, payload);
    } else {
      if (node.rightChild > kKdCompactMaxPayload) throw std::length_error("kd-compact: too many nodes");
      packed = encodeKdCompactNode(node.split, node.axis, node.rightChild);
    }
    glm::vec4& texel = out.nodes[i / 2];
    if (i & 1) {
      texel.z = packed.x;
      texel.w = packed.y;
    } else {
      texel.x = packed.x;
      texel.y = packed.y;
    }
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  out.floatsPerTriangle =
      triangleCount == 0 ? 0.0
                         : (2.0 * static_cast<double>(tree.nodes.size()) + static_cast<double>(out.listEntries)) /
                               static_cast<double>(triangleCount);
  return out;
}

double kdFloatsPerTriangle(const KdTree& tree, size_t triangleCount, uint32_t nodeStride) {
  if (triangleCount == 0) return 0.0;
  size_t entries = 0;
  for (const KdNode& node : tree.nodes)
    if (node.isLeaf() && node.refCount > 0) entries += node.refCount + 1;
  return (4.0 * nodeStride * static_cast<double>(tree.nodes.size()) + static_cast<double>(entries)) /
         static_cast<double>(triangleCount);
}

}  // namespace passtrace
