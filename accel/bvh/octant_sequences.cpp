#include "accel/bvh/octant_sequences.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace passtrace {

Bvh bvhFromBinaryBvh(const BinaryBvh& binary, std::span<const Triangle> tris) {
  Bvh bvh;
  if (binary.empty()) return bvh;
  const auto addNode = [&](const Aabb& box) {
    bvh.nodes.push_back(BvhNode{.box = box});
    return static_cast<uint32_t>(bvh.nodes.size() - 1);
  };
  const auto addLeaf = [&](uint32_t triangle) {
    const uint32_t index = addNode(tris[triangle].bounds());
    bvh.nodes[index].triangle = triangle;
    return index;
  };
  // The node's children, grouped in Bvh::children; a leaf slot of several references becomes a node over them.
  const auto setChildren = [&](uint32_t parent, const std::vector<uint32_t>& kids) {
    bvh.nodes[parent].firstChild = static_cast<uint32_t>(bvh.children.size());
    bvh.nodes[parent].childCount = static_cast<uint32_t>(kids.size());
    bvh.children.insert(bvh.children.end(), kids.begin(), kids.end());
  };

  std::vector<std::pair<uint32_t, uint32_t>> work{{0u, addNode(binary.bounds)}};  // (binary node, Bvh node)
  while (!work.empty()) {
    const auto [from, to] = work.back();
    work.pop_back();
    std::vector<uint32_t> kids;
    for (const BvhChild& child : binary.nodes[from].child) {
      if (!child.present) continue;
      if (!child.isLeaf()) {
        const uint32_t node = addNode(child.box);
        kids.push_back(node);
        work.emplace_back(child.index, node);
      } else if (child.count == 1) {
        kids.push_back(addLeaf(binary.references[child.index]));
      } else {
        const uint32_t group = addNode(child.box);
        std::vector<uint32_t> leaves;
        for (uint32_t r = 0; r < child.count; ++r) leaves.push_back(addLeaf(binary.references[child.index + r]));
        setChildren(group, leaves);
        kids.push_back(group);
      }
    }
    setChildren(to, kids);
  }
  return bvh;
}

namespace {

glm::vec3 octantDiagonal(uint32_t octant) {
  return {(octant & 1u) ? -1.0f : 1.0f, (octant & 2u) ? -1.0f : 1.0f, (octant & 4u) ? -1.0f : 1.0f};
}

// A child's sort key: its quantized box's centre (twice it, in grid units:
// exact integers) along the diagonal, where a ray of this octant reaches
// smaller values first.
float orderKey(const glm::vec3& quantized, const glm::vec3& diagonal) {
  const Aabb planes = BoxGrid::gridPlanes(quantized);
  return glm::dot(planes.min + planes.max, diagonal);
}

}  // namespace

Bvh orderChildrenForOctant(const Bvh& bvh, uint32_t octant, const BoxGrid& grid) {
  Bvh ordered = bvh;
  std::vector<float> keys(bvh.nodes.size());
  for (size_t i = 0; i < bvh.nodes.size(); ++i) keys[i] = orderKey(grid.encode(bvh.nodes[i].box), octantDiagonal(octant));
  for (const BvhNode& node : ordered.nodes) {
    uint32_t* first = ordered.children.data() + node.firstChild;
    std::stable_sort(first, first + node.childCount, [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  }
  return ordered;
}

BoxGrid octantBoxGrid(const Bvh& bvh) { return bvh.empty() ? BoxGrid{} : BoxGrid::over(bvh.nodes[0].box); }

OctantZero flattenOctantZero(const Bvh& bvh, std::span<const Triangle> tris) {
  if (bvh.empty()) return {};
  const BoxGrid grid = octantBoxGrid(bvh);
  const Bvh zero = orderChildrenForOctant(bvh, 0, grid);
  const std::vector<uint32_t> slots = leafSlots(zero);
  OctantZero out{flattenEscapeSequence(zero, tris, LeafTexels::Shared, slots, &grid),
                 sharedTriangleTexels(zero, tris, slots), {}};
  out.slotTriangles.reserve(out.triangles.size() / 2);
  for (size_t slot = 0; 2 * slot < out.triangles.size(); ++slot)
    out.slotTriangles.push_back(unpackIndex(out.triangles[2 * slot].w));
  return out;
}

void writeOctantSequences(const OctantZero& zero, std::span<const Triangle> tris,
                          const std::function<void(uint64_t first, std::span<const glm::vec4> texels)>& write) {
  const std::vector<glm::vec4>& source = zero.sequence.texels;
  const uint64_t size = source.size();
  if (size == 0) return;
  const BoxGrid& grid = *zero.sequence.grid;
  const auto isBox = [&](uint32_t i) { return source[i].w >= 0.0f; };
  const auto end = [&](uint32_t i) { return isBox(i) ? unpackIndex(source[i].w) : i + 1; };  // after i's subtree
  // Leaves carry no box: theirs is their triangle's, as the tree's leaves had.
  const auto quantized = [&](uint32_t i) {
    if (isBox(i)) return glm::vec3(source[i]);
    return grid.encode(tris[zero.slotTriangles[unpackIndex(-source[i].w)]].bounds());
  };
  std::vector<glm::vec4> chunk(kOctantWriteTexels);
  for (uint32_t octant = 0; octant < kOctants; ++octant) {
    const glm::vec3 diagonal = octantDiagonal(octant);
    uint64_t chunkFirst = 0;  // the chunk's first texel within the sequence
    size_t filled = 0;
    std::vector<uint32_t> stack{0};  // indices into sequence 0, in pre-order
    std::vector<std::pair<float, uint32_t>> children;
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      const uint32_t at = uint32_t(chunkFirst + filled);
      if (!isBox(i)) {
        chunk[filled++] = source[i];
      } else {
        // A subtree keeps its size in every order: its escape moves with it.
        const uint32_t escape = end(i);
        chunk[filled++] = glm::vec4(glm::vec3(source[i]), packIndex(at + (escape - i)));
        children.clear();
        for (uint32_t c = i + 1; c < escape; c = end(c))
          children.emplace_back(octant == 0 ? 0.0f : orderKey(quantized(c), diagonal), c);
        // Stable on sequence 0's order: ties as octant 0 has them.
        std::stable_sort(children.begin(), children.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(it->second);
      }
      if (filled == kOctantWriteTexels || stack.empty()) {
        write(octant * size + chunkFirst, std::span<const glm::vec4>(chunk.data(), filled));
        chunkFirst += filled;
        filled = 0;
      }
    }
  }
}

OctantSequences flattenOctantSequences(const Bvh& bvh, std::span<const Triangle> tris) {
  return octantSequencesFrom(flattenOctantZero(bvh, tris), tris);
}

OctantSequences octantSequencesFrom(OctantZero zero, std::span<const Triangle> tris) {
  OctantSequences out;
  out.sequenceTexels = zero.sequence.texels.size();
  out.grid = zero.sequence.grid.value_or(BoxGrid{});
  out.texels.resize(kOctants * out.sequenceTexels);
  writeOctantSequences(zero, tris, [&](uint64_t first, std::span<const glm::vec4> texels) {
    std::copy(texels.begin(), texels.end(), out.texels.begin() + std::ptrdiff_t(first));
  });
  out.triangles = std::move(zero.triangles);
  return out;
}

}  // namespace passtrace
