#include "accel/kd/kd_ropes.h"

#include <span>
#include <utility>

#include "accel/reference_lists.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

// Pushes a rope from `leaf`'s face f down while a child of its target still
// covers the face: a child across the face's own axis is taken on the side
// touching the face; one across another axis only if its half holds the
// leaf's whole extent along that axis.
uint32_t pushDown(const KdTree& tree, const Aabb& leaf, int f, uint32_t rope) {
  const uint32_t axis = uint32_t(f / 2);
  const bool maxSide = (f & 1) != 0;
  while (rope != kNoHit && !tree.nodes[rope].isLeaf()) {
    const KdNode& n = tree.nodes[rope];
    const uint32_t left = rope + 1, right = n.rightChild;
    if (n.axis == axis) {
      rope = maxSide ? left : right;
    } else if (n.split <= leaf.min[n.axis]) {
      rope = right;
    } else if (n.split >= leaf.max[n.axis]) {
      rope = left;
    } else {
      break;  // the face spans both children
    }
  }
  return rope;
}

}  // namespace

std::vector<KdLeafRopes> buildKdRopes(const KdTree& tree) {
  KdLeafRopes none;
  none.fill(kNoHit);
  std::vector<KdLeafRopes> ropes(tree.nodes.size(), none);
  if (tree.empty()) return ropes;
  // Explicit work stack of (node, the ropes of its faces): a child inherits
  // its parent's ropes, and its face on the split plane ropes to its sibling.
  std::vector<std::pair<uint32_t, KdLeafRopes>> work = {{0u, none}};
  while (!work.empty()) {
    auto [index, inherited] = work.back();
    work.pop_back();
    const KdNode& node = tree.nodes[index];
    if (node.isLeaf()) {
      for (int f = 0; f < kKdFaces; ++f) ropes[index][f] = pushDown(tree, node.box, f, inherited[f]);
      continue;
    }
    KdLeafRopes below = inherited, above = inherited;
    below[2 * node.axis + 1] = node.rightChild;
    above[2 * node.axis] = index + 1;
    work.push_back({node.rightChild, above});
    work.push_back({index + 1, below});
  }
  return ropes;
}

KdRopesTexels flattenKdRopes(const KdTree& tree, const std::vector<KdLeafRopes>& ropes, size_t triangleCount) {
  KdRopesTexels out;
  out.offsets.resize(tree.nodes.size());
  uint32_t offset = 0;
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    out.offsets[i] = offset;
    offset += tree.nodes[i].isLeaf() ? kKdRopesLeafTexels : kKdRopesInternalTexels;
  }
  const auto rope = [&](uint32_t target) { return target == kNoHit ? -1.0f : packIndex(out.offsets[target]); };
  out.nodes.reserve(offset);
  ReferenceLists lists;
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode& node = tree.nodes[i];
    if (!node.isLeaf()) {
      out.nodes.emplace_back(packIndex(out.offsets[node.rightChild]), node.split, 0.0f,
                             -(static_cast<float>(node.axis) + 2.0f));
      continue;
    }
    float list = -1.0f;
    if (node.refCount > 0)
      list = packIndex(lists.append(std::span<const uint32_t>(tree.references.data() + node.firstRef, node.refCount)));
    const KdLeafRopes& r = ropes[i];
    out.nodes.emplace_back(rope(r[0]), rope(r[2]), rope(r[4]), list);
    out.nodes.emplace_back(rope(r[1]), rope(r[3]), rope(r[5]), 0.0f);
    out.nodes.emplace_back(node.box.min, 0.0f);
    out.nodes.emplace_back(node.box.max, 0.0f);
  }
  out.lists = lists.texels();
  out.listEntries = lists.entries().size();
  if (triangleCount > 0)
    out.floatsPerTriangle = (4.0 * static_cast<double>(out.nodes.size()) + static_cast<double>(out.listEntries)) /
                            static_cast<double>(triangleCount);
  return out;
}

}  // namespace passtrace
